// The measured form of one axis: `frf_file: FILE.uff` (with `moving_mass_kg`, `band_hz`,
// `max_order`, `response_node`) becomes the modal form of the modes identified from the
// file's FRF records along the axis (docs/scenario-reference.md, docs/measured-data.md).
#pragma once

#include <string>
#include <vector>

#include "bench/config/node_reader.h"
#include "bench/measured/frf_identification.h"
#include "model/machine.h"

namespace shapebench::bench {

// The keys of the measured form.
const std::vector<std::string>& FrfFormKeys();

// The modal form identified from the file named by `frf_file` (relative to the file that
// names it; from --set, to the current directory), its records along `axis` (0, 1, 2).
// gain_r = moving_mass_kg x Re R_r for an FRF per N (the moving body's inertia m a is the
// force), -Re R_r for one per m/s^2 (the base acceleration of the modal form's equation).
model::ModalMachineConfig ReadFrfMachine(const NodeReader& machine, int axis);

// What an axis' measured model was identified from: the file's FRFs and the record whose
// modal constants became the gains. `bode` overlays them on the identified model.
struct MeasuredAxisFrf {
  int axis = 0;
  std::string file;
  std::size_t record = 0;  // into frfs.frfs and frfs.identification.fits
  IdentifiedFrfs frfs;
};

// While one is alive on a thread, ReadFrfMachine keeps what it identified there (the
// identification runs once, when the scenario loads; this keeps it for the views).
class MeasuredFrfCapture {
 public:
  MeasuredFrfCapture();
  ~MeasuredFrfCapture();
  MeasuredFrfCapture(const MeasuredFrfCapture&) = delete;
  MeasuredFrfCapture& operator=(const MeasuredFrfCapture&) = delete;
  const std::vector<MeasuredAxisFrf>& axes() const { return axes_; }

 private:
  friend model::ModalMachineConfig ReadFrfMachine(const NodeReader& machine, int axis);
  std::vector<MeasuredAxisFrf> axes_;
  MeasuredFrfCapture* outer_ = nullptr;
};

}  // namespace shapebench::bench
