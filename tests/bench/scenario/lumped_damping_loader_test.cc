// Reading a lumped axis' `damping:` block (machine_reader.cc): modal ratios and Rayleigh
// coefficients, their located errors, a dashpot beside a block, `shapebench modes`.
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/scenario/scenario_loader.h"
#include "tests/support/bench_test_support.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ExpectError;
using testing::RunCli;
using testing::ScratchDir;

const std::string kLumpedMovingColumn =
    std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/machines/moving_column.yaml";

ConfigError LoadLumpedMachineError(const std::string& path, const std::vector<std::string>& sets = {}) {
  return testing::ErrorOf([&] { LoadMachineAxes(path, ParseOverrides(sets)); });
}

// The chain of data/machines/damped_chain.yaml without its damping line; `extra` follows.
std::string Chain(const std::string& guides_damping, const std::string& extra) {
  return "bodies:\n"
         "  - {name: bed, mass_kg: 400.0}\n"
         "  - {name: column, mass_kg: 150.0}\n"
         "elements:\n"
         "  - {name: mounts, from: bed, to: ground, stiffness_n_m: 8.0e+7}\n"
         "  - {name: guides, from: column, to: driven, stiffness_n_m: 6.0e+6" +
         guides_damping +
         "}\n"
         "driven_relative_to: bed\n"
         "output: {body: column, relative_to: bed}\n" +
         extra;
}

// Tests that both blocks are read into the lumped form and that `modes --json` reports
// the requested ratios for the modal one.
TEST(LumpedDampingLoader, ReadsBlocksAndModesReportsThem) {
  const model::MachineConfig modal = LoadMachine(DataPath("machines/damped_chain.yaml"), {});
  const auto& lumped = std::get<model::LumpedMachineConfig>(modal.form);
  EXPECT_EQ(lumped.damping.kind, model::LumpedDampingKind::kModal);
  EXPECT_EQ(lumped.damping.modal, (std::vector<double>{0.02, 0.045, 0.011}));

  ScratchDir dir;
  const model::MachineConfig rayleigh = LoadMachine(
      dir.Write("r.yaml", Chain("", "damping: {rayleigh: {alpha: 3.5, beta: 2.0e-5}}\n")), {});
  const auto& r = std::get<model::LumpedMachineConfig>(rayleigh.form).damping;
  EXPECT_EQ(r.kind, model::LumpedDampingKind::kRayleigh);
  EXPECT_EQ(r.rayleigh.alpha, 3.5);
  EXPECT_EQ(r.rayleigh.beta, 2.0e-5);

  const testing::CliResult out =
      RunCli({"modes", DataPath("machines/damped_chain.yaml"), "--json"}, SHAPEBENCH_SOURCE_DIR);
  ASSERT_EQ(out.exit_code, 0) << out.err;
  const nlohmann::json json = nlohmann::json::parse(out.out);
  ASSERT_EQ(json["modes"].size(), 3u);
  const std::vector<double> zeta = {0.02, 0.045, 0.011};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(json["modes"][i]["damping_ratio"].get<double>(), zeta[i], 1e-9) << i;
  }
}

// Tests that a dashpot on an axis with a damping block is an error at the dashpot's
// damping_n_s_m that names the block and where it is; the same through --set, and for
// modal and rayleigh given together.
TEST(LumpedDampingLoader, DashpotBesideBlockIsLocated) {
  ScratchDir dir;
  const std::string both =
      dir.Write("b.yaml", Chain(", damping_n_s_m: 300.0", "damping: {modal: [0.03]}\n"));
  ExpectError(LoadLumpedMachineError(both), both, 6, 84, "machine.elements[1].damping_n_s_m",
              "element \"guides\" has a dashpot and the axis has 'damping.modal' (at " + both +
                  ":9:18)");

  // The shipped moving column has dashpots on every axis: a block added by --set meets
  // the first of them, in the machine file.
  const ConfigError added = LoadLumpedMachineError(kLumpedMovingColumn, {"axes.y.damping.modal=[0.03]"});
  EXPECT_EQ(added.file(), kLumpedMovingColumn) << added.what();
  EXPECT_EQ(added.key_path(), "machine.axes.y.elements[0].damping_n_s_m") << added.what();
  EXPECT_NE(added.message().find("'damping.modal' (at --set:1:1)"), std::string::npos)
      << added.what();

  const std::string two = dir.Write(
      "t.yaml", Chain("", "damping:\n  modal: [0.03]\n  rayleigh: {alpha: 1.0}\n"));
  ExpectError(LoadLumpedMachineError(two), two, 11, 13, "machine.damping.rayleigh",
              "'rayleigh' and 'modal' (at " + two + ":10:10) both set this axis' damping");
}

// Tests that the block's own errors are located: an unknown key, an empty list, a ratio out
// of range (validate()), too many ratios for the modes, a negative Rayleigh coefficient,
// and a damping block on a modal axis.
TEST(LumpedDampingLoader, BlockErrorsAreLocated) {
  ScratchDir dir;
  const std::string unknown = dir.Write("u.yaml", Chain("", "damping: {hysteretic: 0.02}\n"));
  ExpectError(LoadLumpedMachineError(unknown), unknown, 9, 11, "machine.damping.hysteretic",
              "unknown key 'hysteretic'; allowed: modal, rayleigh");
  const std::string empty = dir.Write("e.yaml", Chain("", "damping: {modal: []}\n"));
  ExpectError(LoadLumpedMachineError(empty), empty, 9, 18, "machine.damping.modal",
              "expected a list of damping ratios");
  const std::string range = dir.Write("r.yaml", Chain("", "damping: {modal: [0.02, 1.5]}\n"));
  ExpectError(LoadLumpedMachineError(range), range, 9, 25, "machine.damping.modal[1]",
              "must be in [0, 1) (underdamped) (got 1.5)");
  const std::string many =
      dir.Write("m.yaml", Chain("", "damping: {modal: [0.02, 0.03, 0.04]}\n"));
  ExpectError(LoadLumpedMachineError(many), many, 9, 18, "machine.damping.modal",
              "lists 3 damping ratios; the axis has 2 modes");
  const std::string beta =
      dir.Write("n.yaml", Chain("", "damping:\n  rayleigh: {alpha: 2.0, beta: -1.0e-5}\n"));
  ExpectError(LoadLumpedMachineError(beta), beta, 10, 32, "machine.damping.rayleigh.beta",
              "must be finite and >= 0");
  const std::string modal_form = dir.Write(
      "f.yaml", "modes: [{frequency_hz: 25}]\ndamping: {modal: [0.02]}\n");
  ExpectError(LoadLumpedMachineError(modal_form), modal_form, 2, 10, "machine.damping",
              "'damping' belongs to the lumped form");
}

}  // namespace
}  // namespace shapebench::bench
