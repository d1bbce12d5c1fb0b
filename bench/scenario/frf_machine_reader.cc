// ReadFrfMachine (bench/scenario/frf_machine_reader.h).
#include "bench/scenario/frf_machine_reader.h"

#include <cmath>
#include <optional>

#include "bench/measured/frf_identification.h"
#include "bench/config/input_path.h"
#include "bench/config/override.h"
#include "common/format.h"
#include "model/integrator.h"

namespace shapebench::bench {
namespace {

thread_local MeasuredFrfCapture* g_measured_capture = nullptr;

// The record whose modal constants become the gains: `response_node` if given, the only
// record along the axis, or the driving point (response = reference DOF) among several.
std::size_t ChooseRecord(const IdentifiedFrfs& frfs, const NodeReader& machine, const std::string& path) {
  const auto node = machine.Child("response_node");
  std::vector<std::size_t> candidates;
  std::string nodes;
  for (std::size_t k = 0; k < frfs.records.size(); ++k) {
    const Uff58Record& record = frfs.file.records[frfs.records[k]];
    nodes += (nodes.empty() ? "" : ", ") + std::to_string(record.response_node) + " (line " +
             std::to_string(record.line) + ")";
    const bool driving = record.response_node == record.reference_node &&
                         std::abs(record.response_direction) == std::abs(record.reference_direction);
    if (node ? record.response_node == static_cast<int>(node->AsNumber()) : driving) candidates.push_back(k);
  }
  if (frfs.records.size() == 1 && !node) return 0;
  if (candidates.size() == 1) return candidates.front();
  const std::string listed = "the records along the axis in " + path + " respond at nodes " + nodes;
  if (node) {
    throw node->Error(std::string(candidates.empty() ? "no record" : "several records") +
                      " with this response node; " + listed);
  }
  throw machine.Child("frf_file")->Error("several FRF records respond along the axis and none (or more than one) is "
                                         "the driving point: choose one with response_node; " + listed);
}

FrfSelection ReadSelection(const NodeReader& machine, int axis) {
  FrfSelection selection;
  selection.axis = axis;
  if (const auto band = machine.Child("band_hz")) {
    const std::vector<NodeReader> ends = band->Elements();
    if (ends.size() != 2) throw band->Error("expected [min, max] in Hz");
    selection.min_frequency_hz = ends[0].AsNumber();
    selection.max_frequency_hz = ends[1].AsNumber();
    if (!(selection.min_frequency_hz >= 0.0) || !(selection.max_frequency_hz > selection.min_frequency_hz)) {
      throw band->Error("expected 0 <= min < max in Hz");
    }
    selection.band_source = "band_hz";
  }
  if (const auto order = machine.Child("max_order")) {
    const double value = order->AsNumber();
    if (!(value >= 1.0 && value <= 200.0) || value != static_cast<int>(value)) {
      throw order->Error("expected an integer in [1, 200] (pole pairs of the highest model order)");
    }
    selection.max_order = static_cast<int>(value);
  }
  selection.max_work_key = (machine.path().empty() ? "" : machine.path() + ".") + "max_work";
  if (const auto work = machine.Child("max_work")) {
    selection.max_work = work->AsNumber();
    if (!(selection.max_work >= 1.0) || !std::isfinite(selection.max_work)) {
      throw work->Error("expected a number >= 1 (multiply-adds the identification may take; default " +
                        FormatNumber(model::kDefaultIdentificationWork) + ")");
    }
  }
  return selection;
}

// Modes that do not explain the data would make every verdict of the run a verdict on
// a different machine: refused as solver trouble (exit 3, as identify's --max-fit-error),
// located at frf_file and naming the key that allows more.
void CheckFitError(const NodeReader& machine, const NodeReader& frf_file, const std::string& path,
                   const model::ModalIdentification& identification) {
  double limit = kDefaultMaxFitErrorPercent;
  if (const auto key = machine.Child("max_fit_error_percent")) {
    limit = key->AsNumber();
    if (!(limit > 0.0) || !std::isfinite(limit)) throw key->Error("expected a number > 0 (percent of the data's norm)");
  }
  const double error = identification.fit_error_percent;
  if (!(error > limit)) return;
  const std::size_t modes = identification.modes.size();
  throw model::SolverError(
      "FIT_ERROR_ABOVE_LIMIT",
      frf_file.Error("the modes identified from " + path + " leave a fit error of " + FormatNumber(error, 4) +
                     " %, above max_fit_error_percent (" + FormatNumber(limit, 4) + " %) with " +
                     std::to_string(modes) + " mode" + (modes == 1 ? "" : "s") +
                     ": they do not explain the data; narrow band_hz around the peaks of interest, raise "
                     "max_order, or raise max_fit_error_percent")
          .what());
}

}  // namespace

const std::vector<std::string>& FrfFormKeys() {
  static const std::vector<std::string> kKeys = {"frf_file", "moving_mass_kg", "band_hz", "max_order",
                                                 "max_work", "response_node", "max_fit_error_percent"};
  return kKeys;
}

MeasuredFrfCapture::MeasuredFrfCapture() : outer_(g_measured_capture) { g_measured_capture = this; }
MeasuredFrfCapture::~MeasuredFrfCapture() { g_measured_capture = outer_; }

model::ModalMachineConfig ReadFrfMachine(const NodeReader& machine, int axis) {
  const NodeReader frf_file = *machine.Child("frf_file");
  const std::string path = ResolvedInputPath(frf_file);
  const FrfSelection selection = ReadSelection(machine, axis);
  const auto mass = machine.Child("moving_mass_kg");
  const IdentifiedFrfs frfs = IdentifyFrfFile(path, selection);
  const bool per_force = frfs.excitation == FrfExcitation::kForce;
  double mass_kg = 0.0;
  if (per_force) {
    if (!mass) {
      throw frf_file.Error("missing moving_mass_kg: " + path + " holds FRFs per N (an impact or shaker test), whose "
                           "modal constants become gains through the moving body's inertia m a; give its mass");
    }
    mass_kg = mass->AsNumber();
    if (!(mass_kg > 0.0)) throw mass->Error("must be > 0 (kg)");
  } else if (mass) {
    throw mass->Error(path + " holds transmissibilities (per m/s2 of base acceleration): their modal constants are "
                      "the gains, no mass is needed; remove moving_mass_kg");
  }
  const std::size_t chosen = ChooseRecord(frfs, machine, path);
  if (frfs.identification.modes.empty()) {
    throw frf_file.Error("no mode identified from " + path + " in the band (no cluster of stable physical poles); "
                         "run `shapebench identify " + path + "` to see the stabilisation diagram");
  }
  CheckFitError(machine, frf_file, path, frfs.identification);
  if (g_measured_capture != nullptr) g_measured_capture->axes_.push_back({axis, path, chosen, frfs});
  model::ModalMachineConfig modal;
  modal.modes.clear();
  for (const model::IdentifiedMode& mode : frfs.identification.modes) {
    const double constant = mode.modal_constants[chosen].real();
    modal.modes.push_back({mode.frequency_hz, mode.damping_ratio, per_force ? mass_kg * constant : -constant});
  }
  return modal;
}

}  // namespace shapebench::bench
