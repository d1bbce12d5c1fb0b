// What `shapebench bode FILE` shows (bench/cli/bode_command.cc): the frequency response of
// the machine model per axis, the shaping pattern's residual vibration V(f, zeta) and phase
// on the same frequency axis, and for a measured machine (`frf_file`) the measured FRF with
// the identified model's synthesis and its fit error (docs/bode.md).
#pragma once

#include <complex>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/scenario/frf_machine_reader.h"
#include "bench/scenario/scenario.h"
#include "controller/impulse.h"

namespace shapebench::bench {

// One modelled axis: its deflection per unit commanded acceleration along it, H(j 2 pi f)
// = C (j w I - A)^-1 (B_accel + B_vel / (j w)) of the machine's linear plant (the row of
// the axis' deflection, the column of its acceleration; nonlinear elements left out).
struct AxisResponse {
  int axis = 0;
  std::vector<std::complex<double>> response;  // m per m/s^2, at BodeData::frequency_hz
  std::vector<double> mode_frequencies_hz;      // the axis' modes, ascending
};

// The pattern's residual vibration at each frequency with the design damping ratio (a
// fraction of an unshaped step's: controller::ResidualVibration) and the phase of its
// impulses' transfer function sum A_j exp(-j w t_j) / sum A_j.
struct PatternResponse {
  std::string method;
  double damping_ratio = 0.0;
  std::vector<controller::Impulse> impulses;
  std::vector<double> residual;
  std::vector<double> phase_deg;  // unwrapped
};

// A measured axis (MeasuredAxisFrf) over the identification band's lines: the record's
// FRF as measured and as the identified modes synthesise it, in the file's form.
struct MeasuredResponse {
  int axis = 0;
  std::string file;
  std::string units;  // the record's, as the file gives them
  std::vector<double> frequency_hz;
  std::vector<std::complex<double>> measured;
  std::vector<std::complex<double>> identified;
  double fit_error_percent = 0.0;  // ||H_fit - H|| / ||H|| of the record over the band
};

struct BodeData {
  std::vector<double> frequency_hz;  // log-spaced, kBodeLines of them
  std::vector<AxisResponse> axes;
  PatternResponse pattern;
  std::vector<MeasuredResponse> measured;
};

constexpr int kBodeLines = 400;

// `axis` -1: every modelled axis; 0, 1, 2: that one (the caller checks it is modelled).
// The frequencies span a fifth of the lowest mode or design frequency to five times the
// highest (1 to 100 Hz for a rigid machine without a design frequency).
BodeData ComputeBode(const Scenario& scenario, const std::vector<MeasuredAxisFrf>& measured, int axis);

// The response of `plant` from input column `input` to output row `output` at f (Hz).
std::complex<double> PlantResponse(const model::LinearPlant& plant, int output, int input, double frequency_hz);

// Unwrapped phase in degrees of a sequence of complex values.
std::vector<double> UnwrappedPhaseDeg(const std::vector<std::complex<double>>& values);

// {"scenario", "frequency_hz", "axes": [{axis, magnitude_m_per_m_s2, phase_deg, modes_hz}],
//  "pattern": {method, damping_ratio, impulses: [{time_s, amplitude}], residual, phase_deg},
//  "measured": [{axis, file, units, frequency_hz, measured_magnitude, measured_phase_deg,
//  identified_magnitude, identified_phase_deg, fit_error_percent}]}.
nlohmann::ordered_json BodeJson(const BodeData& data, const std::string& scenario_name);

// A short table: per axis its modes and largest |H|, the pattern's V at the design
// frequencies and at the modes, per measured axis its fit error.
void PrintBodeTable(std::ostream& out, const BodeData& data, const Scenario& scenario);

// bode.png: |H| per axis (log-log, left) and V(f) (right) over phase; frf.png (a measured
// machine only): measured against identified, magnitude and phase, the fit error in the
// title. Returns the names written. Throws std::runtime_error when gnuplot fails.
std::vector<std::string> WriteBodePlots(const std::string& dir, const BodeData& data, const std::string& title);

// The same plots as inline SVG for an HTML page: (file name, <svg>) pairs.
std::vector<std::pair<std::string, std::string>> BodePlotsSvg(const BodeData& data, const std::string& title);

}  // namespace shapebench::bench
