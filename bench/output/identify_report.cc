// The identify command's table, JSON, stabilisation diagram (bench/output/identify_report.h).
#include "bench/output/identify_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <stdexcept>
#include <typeinfo>

#include "bench/output/gnuplot.h"
#include "common/atomic_file.h"
#include "common/format.h"
#include "common/shown_text.h"
#include "model/modal_subbands.h"

namespace shapebench::bench {
namespace {

// The modal constant's unit: receptance x (rad/s)^2.
const char* ConstantUnit(const IdentifiedFrfs& frfs) {
  return frfs.excitation == FrfExcitation::kForce ? "1/kg" : "1 (per m/s2 of base acceleration)";
}

std::string Axes(const IdentifiedFrfs& frfs) {
  std::string axes;
  for (std::size_t i : frfs.records) {
    std::string name = DirectionName(frfs.file.records[i].response_direction);
    if (name[0] == '+' || name[0] == '-') name.erase(0, 1);  // the axis, either sense
    if (axes.find(name) == std::string::npos) axes += (axes.empty() ? "" : ", ") + name;
  }
  return axes;
}

}  // namespace

namespace {

// Why a mode is reported, and why a cluster of stable poles is not (the JSON and the table).
std::string KeptWhy(const model::IdentifiedMode& mode) {
  const std::string local =
      mode.local_damping ? "; its peak is narrower than a line: damping fitted on its own neighbourhood" : "";
  if (mode.error_drop > 0.0) {
    return "missed by the diagram, added: it lowers the squared fit error by " +
           FormatNumber(100.0 * mode.error_drop, 3) + " % and its term peaks at " + FormatNumber(mode.prominence, 3) +
           " x the data's RMS in its band" + local;
  }
  return "stable at " + std::to_string(mode.stable_orders) + " orders; its term peaks at " +
         FormatNumber(mode.prominence, 3) + " x the data's RMS in its band (at least " +
         FormatNumber(model::IdentificationOptions{}.min_prominence, 3) + ")" + local;
}

std::string RejectedWhy(const model::RejectedMode& mode) {
  if (mode.error_rise_percent > 0.0) {
    return (mode.stable_orders > 0 ? "stable at " + std::to_string(mode.stable_orders) + " orders"
                                   : std::string("added as missed by the diagram")) +
           ", but removing it raises the fit error by " +
           FormatNumber(mode.error_rise_percent, 3) + " points only (under " +
           FormatNumber(model::IdentificationOptions{}.min_error_rise_percent, 3) + ")";
  }
  return "stable at " + std::to_string(mode.stable_orders) + " orders, but not shown by the data: its term peaks at " +
         FormatNumber(mode.prominence, 3) + " x the data's RMS in its band (under " +
         FormatNumber(model::IdentificationOptions{}.min_prominence, 3) + ")";
}

// How --max-order auto chose the order, in words.
std::string OrderRule(const model::ModalIdentification& id) {
  std::string orders;
  for (int order : id.orders_compared) orders += (orders.empty() ? "" : ", ") + std::to_string(order);
  const std::string tried = "orders " + orders + " compared (doubled from " +
                            std::to_string(model::kFirstAutoOrder) + "): ";
  if (id.order_stop == "settled") {
    return tried + "the modes picked up to " + std::to_string(id.orders_compared[id.orders_compared.size() - 2]) +
           " are those up to " + std::to_string(id.max_order) + " (as many, each frequency within 1 %)";
  }
  return tried + "the modes did not settle before " +
         (id.order_stop == "work" ? "the next order's work passed --max-work" : std::string("the cap")) +
         "; the highest order built is used";
}

// A wide band's sub-bands (model/modal_subbands.h), in words.
std::string SubBandsText(const model::ModalIdentification& id) {
  std::string text = "more than " + std::to_string(model::kMaxLinesPerFit) + " lines: the modes found in " +
                     std::to_string(id.sub_band_orders.size()) + " sub-bands, each on its own (";
  for (std::size_t i = 0; i < id.sub_band_orders.size(); ++i) {
    text += (i == 0 ? "" : ", ") + FormatNumber(id.sub_band_edges_hz[i], 6) + "-" +
            FormatNumber(id.sub_band_edges_hz[i + 1], 6) + " Hz order " + std::to_string(id.sub_band_orders[i]);
  }
  return text + "), their modal constants and residuals fitted on the whole band";
}

// --band auto and --max-order auto: what they chose and why ({} when neither was asked).
nlohmann::ordered_json AutoJson(const IdentifiedFrfs& frfs) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  if (frfs.auto_band) {
    json["band_hz"] = {frfs.auto_band->min_frequency_hz, frfs.auto_band->max_frequency_hz};
    json["peaks_hz"] = frfs.auto_band->peaks_hz;
    json["band_rule"] = frfs.auto_band->rule;
  }
  const model::ModalIdentification& id = frfs.identification;
  if (!id.orders_compared.empty()) {
    json["order"] = id.max_order;
    json["orders_compared"] = id.orders_compared;
    json["order_settled"] = id.order_stop == "settled";
    json["order_rule"] = OrderRule(id);
  }
  return json;
}

}  // namespace

void PrintIdentifyTable(std::ostream& out, const IdentifiedFrfs& frfs) {
  const model::ModalIdentification& id = frfs.identification;
  out << "identify " << TerminalSafe(frfs.file.file, false) << ": " << frfs.records.size() << " FRF record"
      << (frfs.records.size() == 1 ? "" : "s") << " (" << Axes(frfs) << "), "
      << frfs.file.records[frfs.records.front()].units << ", " << FormatNumber(id.frequency_hz.front(), 6) << " to "
      << FormatNumber(id.frequency_hz.back(), 6) << " Hz (" << id.frequency_hz.size() << " lines), orders 1 to "
      << id.max_order << "\n";
  if (frfs.auto_band) out << "band auto: " << TerminalSafe(frfs.auto_band->rule, false) << "\n";
  if (!id.orders_compared.empty()) out << "order auto: " << OrderRule(id) << "\n";
  if (!id.sub_band_orders.empty()) out << "sub-bands: " << SubBandsText(id) << "\n";
  out << "record  line  response  reference  fit_error_percent\n";
  for (std::size_t k = 0; k < frfs.records.size(); ++k) {
    const Uff58Record& record = frfs.file.records[frfs.records[k]];
    out << std::left << std::setw(8) << k + 1 << std::setw(6) << record.line << std::setw(10)
        << (std::to_string(record.response_node) + " " + DirectionName(record.response_direction)) << std::setw(11)
        << (std::to_string(record.reference_node) + " " + DirectionName(record.reference_direction))
        << FormatNumber(id.fits[k].error_percent, 4) << "\n";
  }
  out << "\nmode  frequency_hz  damping_ratio  stable_orders  record  modal_constant_re  modal_constant_im\n";
  for (std::size_t r = 0; r < id.modes.size(); ++r) {
    const model::IdentifiedMode& mode = id.modes[r];
    for (std::size_t k = 0; k < mode.modal_constants.size(); ++k) {
      out << std::left << std::setw(6) << r + 1 << std::setw(14) << FormatNumber(mode.frequency_hz, 6) << std::setw(15)
          << FormatNumber(mode.damping_ratio, 4) << std::setw(15) << mode.stable_orders << std::setw(8) << k + 1
          << std::setw(19) << FormatNumber(mode.modal_constants[k].real(), 5)
          << FormatNumber(mode.modal_constants[k].imag(), 5)
          << "\n";
    }
  }
  if (id.modes.empty()) out << "(no cluster of stable physical poles in the band)\n";
  for (const model::RejectedMode& mode : id.rejected) {
    out << "dropped " << FormatNumber(mode.frequency_hz, 6) << " Hz: " << RejectedWhy(mode) << "\n";
  }
  out << "\nmodal constants R_r of the receptance, " << ConstantUnit(frfs) << "; gain (machine frf_file): "
      << (frfs.excitation == FrfExcitation::kForce ? "moving_mass_kg x Re R_r" : "-Re R_r") << "\n";
  out << "fit error " << FormatNumber(id.fit_error_percent, 4)
      << " % (||H_fit - H|| / ||H|| over the band, every record)\n";
  out.flush();
}

nlohmann::ordered_json IdentifyJson(const IdentifiedFrfs& frfs) {
  const model::ModalIdentification& id = frfs.identification;
  nlohmann::ordered_json json;
  json["file"] = frfs.file.file;
  json["units"] = frfs.file.records[frfs.records.front()].units;
  json["band_hz"] = {id.frequency_hz.front(), id.frequency_hz.back()};
  json["lines"] = id.frequency_hz.size();
  json["max_order"] = id.max_order;
  if (!id.sub_band_orders.empty()) {
    json["sub_bands"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < id.sub_band_orders.size(); ++i) {
      json["sub_bands"].push_back({{"band_hz", {id.sub_band_edges_hz[i], id.sub_band_edges_hz[i + 1]}},
                                   {"order", id.sub_band_orders[i]}});
    }
    json["sub_bands_rule"] = SubBandsText(id);
  }
  json["records"] = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < frfs.records.size(); ++k) {
    const Uff58Record& record = frfs.file.records[frfs.records[k]];
    json["records"].push_back({{"line", record.line},
                               {"response_node", record.response_node},
                               {"response_direction", DirectionName(record.response_direction)},
                               {"reference_node", record.reference_node},
                               {"reference_direction", DirectionName(record.reference_direction)},
                               {"fit_error_percent", id.fits[k].error_percent},
                               {"lower_residual", id.fits[k].lower_residual},
                               {"upper_residual", id.fits[k].upper_residual}});
  }
  json["modes"] = nlohmann::ordered_json::array();
  for (const model::IdentifiedMode& mode : id.modes) {
    nlohmann::ordered_json constants = nlohmann::ordered_json::array();
    for (const auto& c : mode.modal_constants) constants.push_back({{"re", c.real()}, {"im", c.imag()}});
    json["modes"].push_back({{"frequency_hz", mode.frequency_hz},
                             {"damping_ratio", mode.damping_ratio},
                             {"stable_orders", mode.stable_orders},
                             {"prominence", mode.prominence},
                             {"kept", KeptWhy(mode)},
                             {"modal_constants", constants}});
  }
  json["rejected"] = nlohmann::ordered_json::array();
  for (const model::RejectedMode& mode : id.rejected) {
    json["rejected"].push_back({{"frequency_hz", mode.frequency_hz},
                                {"damping_ratio", mode.damping_ratio},
                                {"stable_orders", mode.stable_orders},
                                {"prominence", mode.prominence},
                                {"why", RejectedWhy(mode)}});
  }
  json["refined"] = id.refined;
  json["warnings"] = frfs.warnings;
  json["modal_constant_unit"] = ConstantUnit(frfs);
  json["fit_error_percent"] = id.fit_error_percent;
  if (const nlohmann::ordered_json automatic = AutoJson(frfs); !automatic.empty()) json["auto"] = automatic;
  return json;
}

std::vector<std::string> WriteIdentifyOutputs(const std::string& out_dir, const IdentifiedFrfs& frfs,
                                              const std::string& file) {
  StagedDirectory staged(out_dir);
  const std::filesystem::path dir(staged.path());
  try {
    WriteFileAtomically((dir / "modes.json").string(),
                        [&](std::ostream& out) { out << IdentifyJson(frfs).dump(2) << "\n"; });
    WriteStabilisationPlot((dir / "stabilisation.png").string(), frfs,
                           "stabilisation diagram: " + std::filesystem::path(file).filename().string() + " (" +
                               Axes(frfs) + ")");
  } catch (const std::runtime_error& error) {
    if (typeid(error) != typeid(std::runtime_error)) throw;
    throw std::runtime_error(staged.Shown(error.what()));  // DIR/FILE, not the temporary name
  }
  staged.Commit();
  return {"modes.json", "stabilisation.png"};
}

}  // namespace shapebench::bench
