// The measured form of one axis: `frf_file: FILE.uff` (with `moving_mass_kg`, `band_hz`,
// `max_order`, `response_node`) becomes the modal form of the modes identified from the
// file's FRF records along the axis (docs/scenario-reference.md, docs/measured-data.md).
#pragma once

#include <string>
#include <vector>

#include "bench/config/node_reader.h"
#include "model/machine.h"

namespace shapebench::bench {

// The keys of the measured form.
const std::vector<std::string>& FrfFormKeys();

// The modal form identified from the file named by `frf_file` (relative to the file that
// names it; from --set, to the current directory), its records along `axis` (0, 1, 2).
// gain_r = moving_mass_kg x Re R_r for an FRF per N (the moving body's inertia m a is the
// force), -Re R_r for one per m/s^2 (the base acceleration of the modal form's equation).
model::ModalMachineConfig ReadFrfMachine(const NodeReader& machine, int axis);

}  // namespace shapebench::bench
