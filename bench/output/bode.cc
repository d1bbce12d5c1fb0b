// ComputeBode, BodeJson, PrintBodeTable (bench/output/bode.h).
#include "bench/output/bode.h"

#include <algorithm>
#include <cmath>

#include "bench/output/pattern_report.h"
#include "common/format.h"
#include "common/math_constants.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

// The frequencies that bound the view: every mode of the shown axes, the design ones.
std::vector<double> FrequencyGrid(const std::vector<AxisResponse>& axes, const std::vector<double>& design_hz) {
  std::vector<double> marks = design_hz;
  for (const AxisResponse& axis : axes) {
    marks.insert(marks.end(), axis.mode_frequencies_hz.begin(), axis.mode_frequencies_hz.end());
  }
  marks.erase(std::remove_if(marks.begin(), marks.end(), [](double f) { return !(f > 0.0) || !std::isfinite(f); }),
              marks.end());
  const double low = marks.empty() ? 1.0 : *std::min_element(marks.begin(), marks.end()) / 5.0;
  const double high = marks.empty() ? 100.0 : *std::max_element(marks.begin(), marks.end()) * 5.0;
  std::vector<double> grid(kBodeLines);
  for (int i = 0; i < kBodeLines; ++i) {
    grid[i] = low * std::pow(high / low, static_cast<double>(i) / (kBodeLines - 1));
  }
  return grid;
}

PatternResponse ComputePatternResponse(const controller::ControllerConfig& controller,
                                       const std::vector<double>& frequency_hz) {
  const PatternData data = ComputePattern(controller);
  PatternResponse pattern;
  pattern.method = controller.pattern.method;
  // V(f, zeta) at the damping the pattern is designed for (the first design mode's).
  const std::vector<double> ratios = controller.pattern.DesignDampingRatios();
  pattern.damping_ratio = ratios.empty() ? 0.0 : ratios.front();
  pattern.impulses = data.impulses;
  double total = 0.0;
  for (const controller::Impulse& impulse : data.impulses) total += impulse.amplitude;
  std::vector<std::complex<double>> transfer;
  for (const double f : frequency_hz) {
    pattern.residual.push_back(controller::ResidualVibration(data.impulses, f, pattern.damping_ratio));
    std::complex<double> sum = 0.0;
    for (const controller::Impulse& impulse : data.impulses) {
      sum += impulse.amplitude * std::polar(1.0, -kTwoPi * f * impulse.time_s);
    }
    transfer.push_back(sum / total);
  }
  pattern.phase_deg = UnwrappedPhaseDeg(transfer);
  return pattern;
}

MeasuredResponse ComputeMeasured(const MeasuredAxisFrf& axis) {
  const IdentifiedFrfs& frfs = axis.frfs;
  const model::ModalIdentification& id = frfs.identification;
  MeasuredResponse measured;
  measured.axis = axis.axis;
  measured.file = axis.file;
  measured.units = frfs.file.records[frfs.records[axis.record]].units;
  measured.fit_error_percent = id.fits[axis.record].error_percent;
  // The band's lines among the file's (as the stabilisation plot pairs them).
  std::size_t line = 0;
  for (std::size_t i = 0; i < frfs.frequency_hz.size() && line < id.frequency_hz.size(); ++i) {
    if (frfs.frequency_hz[i] != id.frequency_hz[line]) continue;
    measured.frequency_hz.push_back(frfs.frequency_hz[i]);
    measured.measured.push_back(frfs.frfs[axis.record][i]);
    measured.identified.push_back(id.fits[axis.record].synthesized[line]);
    ++line;
  }
  return measured;
}

nlohmann::ordered_json Magnitudes(const std::vector<std::complex<double>>& values) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& value : values) out.push_back(std::abs(value));
  return out;
}

}  // namespace

std::complex<double> PlantResponse(const model::LinearPlant& plant, int output, int input, double frequency_hz) {
  const int n = plant.num_states();
  if (n == 0) return 0.0;
  const std::complex<double> s(0.0, kTwoPi * frequency_hz);
  // The drive's velocity v = a / s loads the structure through B_vel (lumped dampers).
  const Eigen::VectorXcd b = plant.B_accel.col(input).cast<std::complex<double>>() +
                             plant.B_vel.col(input).cast<std::complex<double>>() / s;
  const Eigen::MatrixXcd system = s * Eigen::MatrixXcd::Identity(n, n) - plant.A.cast<std::complex<double>>();
  const Eigen::VectorXcd x = system.partialPivLu().solve(b);
  return (plant.C.row(output).cast<std::complex<double>>() * x)(0);
}

std::vector<double> UnwrappedPhaseDeg(const std::vector<std::complex<double>>& values) {
  std::vector<double> phase;
  double offset = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double wrapped = std::arg(values[i]) * 180.0 / kPi;
    if (i > 0) {
      const double step = wrapped + offset - phase.back();
      if (step > 180.0) offset -= 360.0;
      if (step < -180.0) offset += 360.0;
    }
    phase.push_back(wrapped + offset);
  }
  return phase;
}

BodeData ComputeBode(const Scenario& scenario, const std::vector<MeasuredAxisFrf>& measured, int axis) {
  BodeData data;
  for (const model::AxisModes& modes : model::AnalyzeMachineModes(scenario.machine)) {
    if (axis >= 0 && modes.axis != axis) continue;
    AxisResponse response;
    response.axis = modes.axis;
    for (const model::ModeInfo& mode : modes.analysis.modes) response.mode_frequencies_hz.push_back(mode.frequency_hz);
    data.axes.push_back(response);
  }
  data.frequency_hz = FrequencyGrid(data.axes, scenario.controller.pattern.DesignFrequencies());
  const model::MachinePlant machine = model::BuildMachinePlant(scenario.machine, scenario.drive);
  for (AxisResponse& response : data.axes) {
    for (const double f : data.frequency_hz) {
      response.response.push_back(
          PlantResponse(machine.plant, model::kDeflectionRow + response.axis, response.axis, f));
    }
  }
  data.pattern = ComputePatternResponse(scenario.controller, data.frequency_hz);
  for (const MeasuredAxisFrf& frf : measured) {
    if (axis < 0 || frf.axis == axis) data.measured.push_back(ComputeMeasured(frf));
  }
  return data;
}

nlohmann::ordered_json BodeJson(const BodeData& data, const std::string& scenario_name) {
  nlohmann::ordered_json json;
  json["scenario"] = scenario_name;
  json["frequency_hz"] = data.frequency_hz;
  json["axes"] = nlohmann::ordered_json::array();
  for (const AxisResponse& axis : data.axes) {
    nlohmann::ordered_json entry;
    entry["axis"] = model::AxisName(axis.axis);
    entry["magnitude_m_per_m_s2"] = Magnitudes(axis.response);
    entry["phase_deg"] = UnwrappedPhaseDeg(axis.response);
    entry["modes_hz"] = axis.mode_frequencies_hz;
    json["axes"].push_back(entry);
  }
  nlohmann::ordered_json pattern;
  pattern["method"] = data.pattern.method;
  pattern["damping_ratio"] = data.pattern.damping_ratio;
  pattern["impulses"] = nlohmann::ordered_json::array();
  for (const controller::Impulse& impulse : data.pattern.impulses) {
    pattern["impulses"].push_back({{"time_s", impulse.time_s}, {"amplitude", impulse.amplitude}});
  }
  pattern["residual"] = data.pattern.residual;
  pattern["phase_deg"] = data.pattern.phase_deg;
  json["pattern"] = pattern;
  json["measured"] = nlohmann::ordered_json::array();
  for (const MeasuredResponse& measured : data.measured) {
    nlohmann::ordered_json entry;
    entry["axis"] = model::AxisName(measured.axis);
    entry["file"] = measured.file;
    entry["units"] = measured.units;
    entry["frequency_hz"] = measured.frequency_hz;
    entry["measured_magnitude"] = Magnitudes(measured.measured);
    entry["measured_phase_deg"] = UnwrappedPhaseDeg(measured.measured);
    entry["identified_magnitude"] = Magnitudes(measured.identified);
    entry["identified_phase_deg"] = UnwrappedPhaseDeg(measured.identified);
    entry["fit_error_percent"] = measured.fit_error_percent;
    json["measured"].push_back(entry);
  }
  return json;
}

void PrintBodeTable(std::ostream& out, const BodeData& data, const Scenario& scenario) {
  out << "frequency response of " << scenario.name << " (" << scenario.source_file << "), "
      << FormatNumber(data.frequency_hz.front(), 4) << " to " << FormatNumber(data.frequency_hz.back(), 4) << " Hz\n";
  for (const AxisResponse& axis : data.axes) {
    std::size_t peak = 0;
    for (std::size_t i = 0; i < axis.response.size(); ++i) {
      if (std::abs(axis.response[i]) > std::abs(axis.response[peak])) peak = i;
    }
    out << "axis " << model::AxisName(axis.axis) << ": " << axis.mode_frequencies_hz.size() << " mode(s)";
    for (const double f : axis.mode_frequencies_hz) out << " " << FormatNumber(f, 5) << " Hz";
    if (!axis.response.empty()) {
      out << "; largest |H| " << FormatNumber(std::abs(axis.response[peak]), 4) << " m per m/s2 at "
          << FormatNumber(data.frequency_hz[peak], 4) << " Hz";
    }
    out << "\n";
  }
  out << "pattern " << data.pattern.method << ": residual vibration V (fraction of an unshaped step's) at zeta "
      << FormatNumber(data.pattern.damping_ratio, 4) << "\n";
  const auto residual = [&](double f) {
    return FormatNumber(controller::ResidualVibration(data.pattern.impulses, f, data.pattern.damping_ratio), 4);
  };
  for (const double f : scenario.controller.pattern.DesignFrequencies()) {
    out << "  design frequency " << FormatNumber(f, 5) << " Hz: " << residual(f) << "\n";
  }
  for (const AxisResponse& axis : data.axes) {
    for (std::size_t m = 0; m < axis.mode_frequencies_hz.size(); ++m) {
      out << "  axis " << model::AxisName(axis.axis) << " mode " << m + 1 << " "
          << FormatNumber(axis.mode_frequencies_hz[m], 5) << " Hz: " << residual(axis.mode_frequencies_hz[m]) << "\n";
    }
  }
  for (const MeasuredResponse& measured : data.measured) {
    out << "measured axis " << model::AxisName(measured.axis) << " (" << measured.file << "): fit error "
        << FormatNumber(measured.fit_error_percent, 4) << " % over " << measured.frequency_hz.size() << " lines\n";
  }
}

}  // namespace shapebench::bench
