// `shapebench identify` and the machine key frf_file through the built CLI: the table,
// JSON and stabilisation diagram, bad UFF input located at its record and line (exit 2),
// the real measured beam of tests/data/uff/, and the modal form a scenario gets.
#include <cmath>
#include <complex>
#include <filesystem>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/scenario/scenario_loader.h"
#include "bench/measured/uff58_reader.h"
#include "tests/support/bench_test_support.h"
#include "tests/support/uff58_writer.h"

namespace shapebench::bench {
namespace {

using testing::CliResult;
using testing::RunCli;
using testing::ScratchDir;
using testing::SyntheticAccelerance;
using testing::SyntheticModes;
using testing::UffFrf;

std::string UffData(const std::string& name) { return std::string(SHAPEBENCH_SOURCE_DIR) + "/tests/data/uff/" + name; }

// The noiseless synthetic accelerance as an ASCII file (complex double).
std::string CleanFile(const ScratchDir& dir, const std::string& name = "clean.uff") {
  return dir.Write(name, testing::Uff58Ascii(SyntheticAccelerance(0.0, 1)));
}

// Expects exit 2 and "error: FILE:LINE:COL: RECORD: ..." containing `part`.
void ExpectLocated(const CliResult& result, const std::string& file, int line, const std::string& record,
                   const std::string& part) {
  EXPECT_EQ(result.exit_code, 2) << result.err;
  const std::string prefix = "error: " + file + ":" + std::to_string(line) + ":";
  EXPECT_EQ(result.err.rfind(prefix, 0), 0u) << result.err;
  EXPECT_NE(result.err.find(": " + record + ": "), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(part), std::string::npos) << result.err;
}

// Tests that identify prints the modes table, writes modes.json and stabilisation.png
// into --out with a wrote line each, and --json prints the same modes as one object.
TEST(IdentifyCli, TableJsonAndDiagram) {
  ScratchDir dir;
  const std::string file = CleanFile(dir);
  const CliResult table = RunCli({"identify", file, "--axis", "y", "--out", "out"}, dir.path().string());
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("mode  frequency_hz  damping_ratio"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("1     22 "), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("fit error "), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("wrote out/modes.json\nwrote out/stabilisation.png\n"), std::string::npos) << table.out;
  EXPECT_EQ(testing::ReadText(dir.File("out/stabilisation.png")).substr(1, 3), "PNG");
  const CliResult json = RunCli({"identify", file, "--json", "--out", "out2"}, dir.path().string());
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json parsed = nlohmann::json::parse(json.out);
  ASSERT_EQ(parsed["modes"].size(), 3u);
  for (std::size_t r = 0; r < 3; ++r) {
    EXPECT_NEAR(parsed["modes"][r]["frequency_hz"].get<double>(), SyntheticModes()[r].frequency_hz, 1e-6 * 41.2);
    EXPECT_NEAR(parsed["modes"][r]["modal_constants"][0]["re"].get<double>(), SyntheticModes()[r].constant, 1e-6);
  }
  EXPECT_LT(parsed["fit_error_percent"].get<double>(), 1e-3);
  EXPECT_NE(json.err.find("wrote out2/stabilisation.png"), std::string::npos) << json.err;  // stdout stays JSON
}

// Tests that a record cut short, a file without dataset 58, a time response, a NaN, a
// hexadecimal value, units that are neither displacement, velocity nor acceleration per
// force or acceleration, and a band without lines are each refused (exit 2) at their record and line.
TEST(IdentifyCli, BadInputIsLocated) {
  ScratchDir dir;
  const std::string clean = testing::Uff58Ascii(SyntheticAccelerance(0.0, 1));
  const std::string cwd = dir.path().string();
  // Truncated: the dataset closes after 100 of its data lines (13 header lines first).
  std::string truncated;
  std::size_t at = 0;
  for (int line = 0; line < 113; ++line) at = clean.find('\n', at) + 1;
  truncated = clean.substr(0, at) + "    -1\n";
  ExpectLocated(RunCli({"identify", dir.Write("t.uff", truncated)}, cwd), dir.File("t.uff"), 114, "record 12",
                "truncated: record 7 announces 801 values");
  // Only a dataset 55 (a mode shape), no 58.
  ExpectLocated(RunCli({"identify", dir.Write("d.uff", "    -1\n    55\nNONE\n    -1\n")}, cwd), dir.File("d.uff"), 2,
                "dataset", "no dataset 58 (function at nodal DOF) in the file, only dataset 55");
  UffFrf time = SyntheticAccelerance(0.0, 1);
  time.function_type = 1;
  ExpectLocated(RunCli({"identify", dir.Write("f.uff", testing::Uff58Ascii(time))}, cwd), dir.File("f.uff"), 8,
                "record 6", "function type 1 (time response) is not a frequency response function (4)");
  std::string with_nan = clean;
  const std::size_t value = with_nan.find("\n", with_nan.find("NONE                 NONE")) + 1;  // record 12
  with_nan.replace(value + 60, 20, "                 nan");  // 0.125 Hz, inside the default band
  ExpectLocated(RunCli({"identify", dir.Write("n.uff", with_nan)}, cwd), dir.File("n.uff"), 14, "record 12",
                "value nan at 0.125 Hz is not a finite number and lies in the band [0, inf] Hz");
  // A decimal Fortran real only (issue 32 item 16): strtod read "0x10" as 16.
  std::string with_hex = clean;
  with_hex.replace(value + 20, 20, "                0x10");
  const CliResult hex_value = RunCli({"identify", dir.Write("h.uff", with_hex)}, cwd);
  ExpectLocated(hex_value, dir.File("h.uff"), 14, "record 12", "expected a number in columns 21-40, got");
  EXPECT_NE(hex_value.err.find("0x10'"), std::string::npos) << hex_value.err;
  UffFrf pressure = SyntheticAccelerance(0.0, 1);
  pressure.numerator_type = 15;
  pressure.numerator_units = "Pa";
  ExpectLocated(RunCli({"identify", dir.Write("u.uff", testing::Uff58Ascii(pressure))}, cwd), dir.File("u.uff"), 11,
                "record 9", "unknown ordinate units: specific data type 15, units label 'Pa'");
  ExpectLocated(RunCli({"identify", dir.Write("b.uff", clean), "--band", "150:200"}, cwd), dir.File("b.uff"), 9,
                "record 7", "--band 150:200: 0 spectral lines above 0 Hz in the band [150, 200] Hz");
  ExpectLocated(RunCli({"identify", dir.Write("a.uff", clean), "--axis", "x"}, cwd), dir.File("a.uff"), 8, "record 6",
                "no FRF record has its response along x");
  // Decimal numbers only (issue 32 item 16): "0x10" was read as 16 Hz.
  for (const char* band : {"0x10:200", "5:inf", " 5:200"}) {
    const CliResult hex = RunCli({"identify", dir.File("a.uff"), "--band", band}, cwd);
    EXPECT_EQ(hex.exit_code, 2) << band;
    EXPECT_NE(hex.err.find("--band: expected MIN:MAX in Hz"), std::string::npos) << hex.err;
  }
}

// Tests that a NaN or inf outside the band asked for (at 0 Hz, which no band holds, or above
// --band's top) is ignored with a warning naming its line, while the same value inside
// the band is refused (exit 2) at its line and column.
TEST(IdentifyCli, NonFiniteOutsideTheBandIsIgnored) {
  ScratchDir dir;
  std::string text = testing::Uff58Ascii(SyntheticAccelerance(0.0, 1));
  const std::size_t value = text.find("\n", text.find("NONE                 NONE")) + 1;  // record 12, 0 Hz
  text.replace(value + 20, 20, "                 nan");
  const std::size_t line_90_hz = value + 360 * 81;  // two points a line: 90 Hz (point 720) opens line 14 + 360
  text.replace(line_90_hz, 20, "                 inf");
  const std::string file = dir.Write("n.uff", text);
  const CliResult outside = RunCli({"identify", file, "--band", "5:80", "--out", "o1"}, dir.path().string());
  ASSERT_EQ(outside.exit_code, 0) << outside.err;
  EXPECT_NE(outside.err.find("warning: " + file + ":14:21: record 12: 2 lines with a value that is not a finite number "
                             "(nan at 0 Hz, up to 90 Hz) outside the band [5, 80] Hz: ignored"),
            std::string::npos)
      << outside.err;
  EXPECT_NE(outside.out.find("1     22 "), std::string::npos) << outside.out;
  ExpectLocated(RunCli({"identify", file, "--band", "5:95", "--out", "o2"}, dir.path().string()), file, 374,
                "record 12", "value inf at 90 Hz is not a finite number and lies in the band [5, 95] Hz (--band 5:95)");
}

// Tests that --band auto --max-order auto on the synthetic column (22 Hz 2 %, 40 Hz 3 %,
// 41.2 Hz 1.5 %; a NaN at 0 Hz, ignored with a warning) spans the peaks it names with an
// octave's margin, settles its order, says both in the table and the JSON, and finds the
// three modes within 0.5 % in frequency and 10 % in damping; and that --max-order takes
// only an integer from 1 to 200 or auto (exit 2).
TEST(IdentifyCli, AutoBandAndOrder) {
  ScratchDir dir;
  std::string text = testing::Uff58Ascii(SyntheticAccelerance(0.0, 1));
  const std::size_t value = text.find("\n", text.find("NONE                 NONE")) + 1;  // record 12, 0 Hz
  text.replace(value + 20, 20, "                 nan");
  const std::string file = dir.Write("a.uff", text);
  const CliResult table =
      RunCli({"identify", file, "--band", "auto", "--max-order", "auto", "--out", "o1"}, dir.path().string());
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.err.find("(nan at 0 Hz) outside the band [11, "), std::string::npos) << table.err;
  EXPECT_NE(table.out.find("band auto: from half the lowest to 1.5 x the highest of "), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("order auto: orders 8, 16"), std::string::npos) << table.out;
  const CliResult json = RunCli({"identify", file, "--band", "auto", "--max-order", "auto", "--json", "--out", "o2"},
                                dir.path().string());
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json parsed = nlohmann::json::parse(json.out);
  const nlohmann::json& automatic = parsed["auto"];
  ASSERT_GE(automatic["peaks_hz"].size(), 2u) << automatic.dump();
  EXPECT_NEAR(automatic["peaks_hz"].front().get<double>(), 22.0, 0.125);
  EXPECT_DOUBLE_EQ(automatic["band_hz"][0].get<double>(), 0.5 * automatic["peaks_hz"].front().get<double>());
  EXPECT_DOUBLE_EQ(automatic["band_hz"][1].get<double>(), 1.5 * automatic["peaks_hz"].back().get<double>());
  EXPECT_TRUE(automatic["order_settled"].get<bool>());
  EXPECT_EQ(automatic["order"], parsed["max_order"]);
  ASSERT_EQ(parsed["modes"].size(), 3u) << parsed["modes"].dump(1);
  for (std::size_t r = 0; r < 3; ++r) {
    const double f = SyntheticModes()[r].frequency_hz, zeta = SyntheticModes()[r].damping_ratio;
    EXPECT_NEAR(parsed["modes"][r]["frequency_hz"].get<double>(), f, 0.005 * f);
    EXPECT_NEAR(parsed["modes"][r]["damping_ratio"].get<double>(), zeta, 0.1 * zeta);
  }
  const CliResult bad = RunCli({"identify", file, "--max-order", "2.5"}, dir.path().string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--max-order: expected an integer from 1 to 200 or auto, got '2.5'"), std::string::npos)
      << bad.err;
  EXPECT_EQ(RunCli({"identify", file, "--max-order", "201"}, dir.path().string()).exit_code, 2);
}

// Tests that a fit error above --max-fit-error (default 20 %; here an FRF of noise alone,
// which no mode explains) still writes the output, warns naming the error and the limit
// and exits 3, and that a limit above the error exits 0; and that the JSON says why each
// mode was kept and whether the refinement was.
TEST(IdentifyCli, FitErrorAboveTheLimitExits3) {
  ScratchDir dir;
  UffFrf noise = SyntheticAccelerance(0.0, 1);
  std::mt19937 generator(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (auto& value : noise.values) value = {normal(generator), normal(generator)};
  const std::string file = dir.Write("noise.uff", testing::Uff58Ascii(noise));
  const CliResult bad = RunCli({"identify", file, "--out", "o1"}, dir.path().string());
  EXPECT_EQ(bad.exit_code, 3) << bad.err;
  EXPECT_NE(bad.err.find("warning: " + file + ": fit error "), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find(" % is above --max-fit-error (20 %)"), std::string::npos) << bad.err;
  EXPECT_TRUE(std::filesystem::exists(dir.File("o1/modes.json")));
  const CliResult allowed = RunCli({"identify", file, "--max-fit-error", "100", "--out", "o2"}, dir.path().string());
  EXPECT_EQ(allowed.exit_code, 0) << allowed.err;
  const CliResult clean = RunCli({"identify", CleanFile(dir), "--json", "--out", "o3"}, dir.path().string());
  ASSERT_EQ(clean.exit_code, 0) << clean.err;
  const nlohmann::json parsed = nlohmann::json::parse(clean.out);
  EXPECT_TRUE(parsed["refined"].get<bool>());
  EXPECT_TRUE(parsed["rejected"].empty());
  ASSERT_EQ(parsed["modes"].size(), 3u);
  EXPECT_EQ(parsed["modes"][0]["kept"].get<std::string>().rfind("stable at ", 0), 0u) << clean.out;
  EXPECT_GT(parsed["modes"][0]["prominence"].get<double>(), 0.1);
}

// Tests that a scenario's frf_file machine whose identified modes fit the FRF worse than
// max_fit_error_percent is refused with exit 3, located at frf_file and naming the key,
// before anything runs; the shipped scenario's fit passes the default limit, and a limit
// that is not a positive number is bad input (2) at its key.
TEST(IdentifyCli, FrfMachineAboveItsFitErrorLimitExits3) {
  ScratchDir dir;
  const std::string measurement = kSourceDir + "/configs/measurements/column_y_accelerance.uff";
  const std::string base = "machine:\n  frf_file: " + measurement +
                           "\n  axis: y\n  moving_mass_kg: 2400\n  band_hz: [5, 80]\n";
  const std::string rest = "drive: {type: kinematic}\nmove: {distance_mm: 20}\n";
  const std::string strict = dir.Write("strict.yaml", base + "  max_fit_error_percent: 0.001\n" + rest);
  const CliResult refused = RunCli({"run", strict}, dir.path().string());
  EXPECT_EQ(refused.exit_code, 3) << refused.err;
  EXPECT_NE(refused.err.find("FIT_ERROR_ABOVE_LIMIT"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find(strict + ":2:"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("above max_fit_error_percent (0.001 %)"), std::string::npos) << refused.err;
  EXPECT_TRUE(refused.out.empty()) << refused.out;
  const CliResult passes = RunCli({"run", dir.Write("default.yaml", base + rest), "--json"}, dir.path().string());
  EXPECT_EQ(passes.exit_code, 0) << passes.err;
  const std::string bad = dir.Write("bad.yaml", base + "  max_fit_error_percent: -1\n" + rest);
  ExpectLocated(RunCli({"run", bad}, dir.path().string()), bad, 6, "machine.max_fit_error_percent",
                "expected a number > 0");
}

// Tests that the real measured beam (pyuff's accelerances, tests/data/uff/README.md) gives six
// modes, each physical (damping in (0, 0.5), inside the band) and each within a line (1 Hz) of a
// peak of |H| found in the test by peak picking, with the fit error under 6 %.
TEST(IdentifyCli, RealMeasuredBeam) {
  ScratchDir dir;
  const std::string file = UffData("pyuff_beam_accelerance.uff");
  const CliResult result = RunCli({"identify", file, "--json", "--out", "out"}, dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json parsed = nlohmann::json::parse(result.out);
  // The oracle: local maxima of the driving-point |H| standing out of their +-10 lines.
  const Uff58File read = ReadUff58(file);  // kept: the record below refers into it
  const Uff58Record& record = read.records[0];
  std::vector<double> peaks;
  for (std::size_t i = 10; i + 10 < record.values.size(); ++i) {
    bool top = true;
    for (std::size_t j = i - 10; j <= i + 10; ++j) top = top && std::abs(record.values[j]) <= std::abs(record.values[i]);
    if (top && std::abs(record.values[i]) > 5.0) peaks.push_back(record.frequency_hz[i]);
  }
  ASSERT_EQ(peaks.size(), 6u);
  ASSERT_EQ(parsed["modes"].size(), peaks.size()) << result.out;
  for (std::size_t r = 0; r < peaks.size(); ++r) {
    const double f = parsed["modes"][r]["frequency_hz"].get<double>();
    const double zeta = parsed["modes"][r]["damping_ratio"].get<double>();
    EXPECT_NEAR(f, peaks[r], 1.0);
    EXPECT_GT(zeta, 0.0);
    EXPECT_LT(zeta, 0.5);
  }
  // The synthesis of 6 modes and two residuals leaves 3 % of this measurement unexplained
  // (noise, a 0.1 % damped beam at 1 Hz resolution); 6 % bounds it with margin.
  EXPECT_LT(parsed["fit_error_percent"].get<double>(), 6.0);
}

// Tests that machine: {frf_file, moving_mass_kg} becomes the modal form with
// gain_r = m Re R_r, and that an FRF per N without moving_mass_kg is refused naming it.
TEST(IdentifyCli, MachineFromFrfFile) {
  ScratchDir dir;
  CleanFile(dir, "m/tool.uff");
  const std::string machine = dir.Write("m/machine.yaml", "frf_file: tool.uff\naxis: y\nmoving_mass_kg: 400\n");
  const model::MultiAxisMachineConfig config = LoadMachineAxes(machine, {});
  const auto& modal = std::get<model::ModalMachineConfig>(config.axes[1]->form);
  ASSERT_EQ(modal.modes.size(), 3u);
  for (std::size_t r = 0; r < 3; ++r) {
    EXPECT_NEAR(modal.modes[r].frequency_hz, SyntheticModes()[r].frequency_hz, 1e-6 * 41.2);
    EXPECT_NEAR(modal.modes[r].gain, 400.0 * SyntheticModes()[r].constant, 1e-6);
  }
  const std::string missing = dir.Write("m/missing.yaml", "frf_file: tool.uff\naxis: y\n");
  testing::ExpectError(testing::ErrorOf([&] { LoadMachineAxes(missing, {}); }), missing, 1, 11, "machine.frf_file",
                       "missing moving_mass_kg");
  const std::string both = dir.Write("m/both.yaml", "frf_file: tool.uff\nmodes: [{frequency_hz: 5}]\n");
  testing::ExpectError(testing::ErrorOf([&] { LoadMachineAxes(both, {}); }), both, 2, 8, "machine.modes",
                       "'modes' and 'frf_file' both give this axis' model");
}

// Tests that a transmissibility (acceleration per m/s2 of base acceleration) gives
// gain_r = -Re R_r: a structure whose deflection follows the bench's equation
// q'' + 2 zeta w q' + w^2 q = -a_base, deflection = sum g q, measured as
// deflection per base acceleration, -sum g / (w^2 - W^2 + ...), times (j W)^2.
TEST(IdentifyCli, MachineFromTransmissibility) {
  ScratchDir dir;
  UffFrf frf = SyntheticAccelerance(0.0, 1, -1.0);  // R_r = -g_r
  frf.denominator_type = 12;
  frf.denominator_units = "m/s2";
  dir.Write("t.uff", testing::Uff58Ascii(frf));
  const std::string machine = dir.Write("m.yaml", "frf_file: t.uff\naxis: y\nband_hz: [5, 80]\n");
  const model::MultiAxisMachineConfig config = LoadMachineAxes(machine, {});
  const auto& modal = std::get<model::ModalMachineConfig>(config.axes[1]->form);
  ASSERT_EQ(modal.modes.size(), 3u);
  for (std::size_t r = 0; r < 3; ++r) EXPECT_NEAR(modal.modes[r].gain, SyntheticModes()[r].constant, 1e-8);
  const std::string mass = dir.Write("mass.yaml", "frf_file: t.uff\naxis: y\nmoving_mass_kg: 3\n");
  testing::ExpectError(testing::ErrorOf([&] { LoadMachineAxes(mass, {}); }), mass, 3, 17, "machine.moving_mass_kg",
                       "remove moving_mass_kg");
}

}  // namespace
}  // namespace shapebench::bench
