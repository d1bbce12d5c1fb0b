// Modes identified from a UFF 58 file's FRF records (bench/measured/uff58_reader.h,
// model/modal_identification.h): what `shapebench identify` shows and what the machine key
// `frf_file` turns into a modal form (docs/measured-data.md).
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "bench/measured/uff58_reader.h"
#include "model/modal_band.h"
#include "model/modal_identification.h"

namespace shapebench::bench {

// Above this fit error (percent of the data's norm) the identified modes do not explain
// the data: `identify` warns and exits 3 (--max-fit-error), a scenario's `frf_file`
// machine is refused with exit 3 (its key max_fit_error_percent). The shipped and
// synthetic FRFs fit within 6 %.
inline constexpr double kDefaultMaxFitErrorPercent = 20.0;

struct FrfSelection {
  int axis = -1;  // 0, 1, 2: the records whose response direction is along it; -1 every record
  double min_frequency_hz = 0.0;
  double max_frequency_hz = std::numeric_limits<double>::infinity();
  int max_order = 30;  // pole pairs (model::IdentificationOptions::max_order)
  // --band auto: the band chosen from the records' peaks (model/modal_band.h), the band
  // fields ignored; --max-order auto: model::IdentificationOptions::auto_order, max_order its cap.
  bool auto_band = false;
  bool auto_order = false;
  // model::IdentificationOptions::max_work, and the option or key that sets it (messages).
  double max_work = model::kDefaultIdentificationWork;
  std::string max_work_key = "--max-work";
  // How the band was given, for messages ("--band 5:200", "band_hz"); "" when not given.
  std::string band_source;
};

struct IdentifiedFrfs {
  Uff58File file;
  std::vector<std::size_t> records;  // indices into file.records, the ones identified together
  FrfResponse response = FrfResponse::kAcceleration;
  FrfExcitation excitation = FrfExcitation::kForce;
  std::vector<double> frequency_hz;                      // the records' common grid
  std::vector<std::vector<std::complex<double>>> frfs;  // per record, signs of the directions applied
  model::ModalIdentification identification;
  std::optional<model::AutoBand> auto_band;  // FrfSelection::auto_band's choice
  // "FILE:LINE:COL: record N: ..." the reader's (a writer's quirk read anyway) and values
  // that are not finite outside the band, ignored.
  std::vector<std::string> warnings;
};

// Reads `path`, keeps the records along the selection's axis and identifies them together:
// one set of poles, modal constants per record. Records identified together share their
// frequency lines and units. Throws ConfigError located at the record that is in the way
// (no record along the axis, lines or units that differ, a band with too few lines).
IdentifiedFrfs IdentifyFrfFile(const std::string& path, const FrfSelection& selection);

// "x", "y", "z" or "scalar"/"rotation" with the sense: "+y", "-x".
std::string DirectionName(int direction);

}  // namespace shapebench::bench
