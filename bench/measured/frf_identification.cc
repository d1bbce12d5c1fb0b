// IdentifyFrfFile (bench/measured/frf_identification.h).
#include "bench/measured/frf_identification.h"

#include "bench/config/config_error.h"
#include "common/format.h"
#include "common/validation_error.h"
#include "model/integrator.h"
#include "model/modal_band.h"

namespace shapebench::bench {
namespace {

std::string RecordName(const Uff58Record& record) {
  return "the record at line " + std::to_string(record.line) + " (response " + std::to_string(record.response_node) +
         " " + DirectionName(record.response_direction) + ")";
}

// The records along the axis; an error listing the directions found when none is.
std::vector<std::size_t> SelectRecords(const Uff58File& file, int axis) {
  std::vector<std::size_t> selected;
  std::string found;
  for (std::size_t i = 0; i < file.records.size(); ++i) {
    if (axis < 0 || file.records[i].ResponseAxis() == axis) selected.push_back(i);
    found += (found.empty() ? "" : ", ") + DirectionName(file.records[i].response_direction) + " (line " +
             std::to_string(file.records[i].line) + ")";
  }
  if (selected.empty()) {
    const Uff58Record& first = file.records.front();
    throw ConfigError(file.file, first.record6_line, 52, "record 6",
                      std::string("no FRF record has its response along ") + "xyz"[axis] +
                          " (response directions 1, 2, 3 are x, y, z); the file's records respond along " + found);
  }
  return selected;
}

// Records identified together share lines and units: checked against the first.
void CheckAlike(const Uff58File& file, const std::vector<std::size_t>& selected) {
  const Uff58Record& first = file.records[selected.front()];
  for (std::size_t i : selected) {
    const Uff58Record& record = file.records[i];
    if (record.frequency_hz != first.frequency_hz) {
      throw ConfigError(file.file, record.record7_line, 1, "record 7",
                        "its frequency lines differ from those of " + RecordName(first) +
                            "; records identified together must share them (select one axis with --axis or axis:)");
    }
    if (record.response != first.response || record.excitation != first.excitation) {
      throw ConfigError(file.file, record.record9_line, 1, "record 9",
                        "its units (" + record.units + ") differ from those of " + RecordName(first) + " (" +
                            first.units + "); records identified together must share them");
    }
  }
}

std::string BandText(const FrfSelection& selection) {
  return "[" + FormatNumber(selection.min_frequency_hz, 6) + ", " + FormatNumber(selection.max_frequency_hz, 6) + "] Hz";
}

// Enough lines above 0 Hz inside the band: located at the first record's record 7.
void CheckFrfBand(const Uff58File& file, const Uff58Record& first, const FrfSelection& selection) {
  int lines = 0;
  for (double f : first.frequency_hz) {
    if (f > 0.0 && f >= selection.min_frequency_hz && f <= selection.max_frequency_hz) ++lines;
  }
  if (lines >= 4) return;
  const std::string band = BandText(selection);
  throw ConfigError(file.file, first.record7_line, 1, "record 7",
                    (selection.band_source.empty() ? std::string("the records") : selection.band_source + ":") +
                        " " + std::to_string(lines) + " spectral line" + (lines == 1 ? "" : "s") +
                        " above 0 Hz in the band " + band + ", at least 4 are needed; the records' lines span " +
                        FormatNumber(first.frequency_hz.front(), 6) + " to " +
                            FormatNumber(first.frequency_hz.back(), 6) + " Hz");
}

// NaN or inf values: inside the band (above 0 Hz) refused at the first one's line and
// column; outside it ignored (the identification reads only the band's lines), one warning
// per record.
void CheckNonFinite(const Uff58File& file, const std::vector<std::size_t>& selected, const FrfSelection& selection,
                    std::vector<std::string>* warnings) {
  for (std::size_t i : selected) {
    const Uff58Record& record = file.records[i];
    if (record.non_finite.empty()) continue;
    for (const Uff58NonFinite& bad : record.non_finite) {
      const double f = record.frequency_hz[bad.point];
      if (f > 0.0 && f >= selection.min_frequency_hz && f <= selection.max_frequency_hz) {
        throw ConfigError(file.file, bad.line, bad.column, "record 12",
                          "value " + bad.text + " at " + FormatNumber(f, 6) + " Hz is not a finite number and lies in "
                          "the band " + BandText(selection) + (selection.band_source.empty() ? "" : " (" +
                          selection.band_source + ")") + "; an FRF to identify needs every line of its band "
                          "measured: give a band that leaves it out (--band, band_hz)");
      }
    }
    const Uff58NonFinite& first = record.non_finite.front();
    const double lo = record.frequency_hz[first.point];
    const double hi = record.frequency_hz[record.non_finite.back().point];
    const std::size_t n = record.non_finite.size();
    warnings->push_back(file.file + ":" + std::to_string(first.line) + ":" + std::to_string(first.column) +
                        ": record 12: " + std::to_string(n) + " line" + (n == 1 ? "" : "s") + " with a value that "
                        "is not a finite number (" + first.text + " at " + FormatNumber(lo, 6) + " Hz" +
                        (n == 1 ? "" : ", up to " + FormatNumber(hi, 6) + " Hz") + ") outside the band " +
                        BandText(selection) + ": ignored");
  }
}

}  // namespace

std::string DirectionName(int direction) {
  const int axis = direction < 0 ? -direction : direction;
  const std::string sense = direction < 0 ? "-" : "+";
  if (axis >= 1 && axis <= 3) return sense + "xyz"[axis - 1];
  if (axis >= 4 && axis <= 6) return sense + "r" + "xyz"[axis - 4];
  return "scalar";
}

IdentifiedFrfs IdentifyFrfFile(const std::string& path, const FrfSelection& given) {
  IdentifiedFrfs result;
  result.file = ReadUff58(path);
  result.records = SelectRecords(result.file, given.axis);
  CheckAlike(result.file, result.records);
  const Uff58Record& first = result.file.records[result.records.front()];
  result.response = first.response;
  result.excitation = first.excitation;
  result.frequency_hz = first.frequency_hz;
  for (std::size_t i : result.records) {
    const Uff58Record& record = result.file.records[i];
    std::vector<std::complex<double>> frf = record.values;
    for (auto& value : frf) value *= record.DirectionSign();
    result.frfs.push_back(std::move(frf));
  }
  FrfSelection selection = given;
  if (selection.auto_band) {
    try {
      result.auto_band = model::ChooseBand(result.frequency_hz, result.frfs);
    } catch (const ValidationError& error) {
      throw ConfigError(path, first.record12_line, 1, "record 12", error.message());
    }
    selection.min_frequency_hz = result.auto_band->min_frequency_hz;
    selection.max_frequency_hz = result.auto_band->max_frequency_hz;
    selection.band_source = "--band auto (" + FormatNumber(selection.min_frequency_hz, 6) + ":" +
                            FormatNumber(selection.max_frequency_hz, 6) + ")";
  }
  CheckFrfBand(result.file, first, selection);
  result.warnings = result.file.warnings;
  CheckNonFinite(result.file, result.records, selection, &result.warnings);
  model::IdentificationOptions options;
  options.min_frequency_hz = selection.min_frequency_hz;
  options.max_frequency_hz = selection.max_frequency_hz;
  options.max_order = selection.max_order;
  options.auto_order = selection.auto_order;
  options.max_work = selection.max_work;
  options.max_work_key = selection.max_work_key;
  try {
    result.identification = model::IdentifyModes(result.frequency_hz, result.frfs, first.DerivativeOrder(), options);
  } catch (const ValidationError& error) {
    throw ConfigError(path, first.record12_line, 1, "record 12", error.message());
  } catch (const model::SolverError& error) {  // over its work limit: name the file
    throw model::SolverError(error.flag_name(), path + ": " + error.what());
  }
  return result;
}

}  // namespace shapebench::bench
