// IntegratorConfig validation and MakeIntegrator's choice of method.
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "common/validation_error.h"
#include "model/cvode_integrator.h"
#include "model/exact_integrator.h"
#include "model/integrator.h"
#include "model/machine.h"

namespace shapebench::model {
namespace {

struct ConfigCase {
  std::string name;
  std::function<void(IntegratorConfig&)> spoil;
  std::string field;
};

void PrintTo(const ConfigCase& c, std::ostream* os) { *os << c.name; }

class IntegratorValidation : public testing::TestWithParam<ConfigCase> {};

// Tests that each out-of-range setting is rejected with a ValidationError naming it.
TEST_P(IntegratorValidation, NamesTheField) {
  IntegratorConfig config;
  ASSERT_NO_THROW(config.validate());
  GetParam().spoil(config);
  try {
    config.validate();
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), GetParam().field) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Grid, IntegratorValidation,
    testing::Values(
        ConfigCase{"ZeroRtol", [](IntegratorConfig& c) { c.rtol = 0.0; }, "rtol"},
        ConfigCase{"LooseRtol", [](IntegratorConfig& c) { c.rtol = 0.02; }, "rtol"},
        ConfigCase{"NanRtol", [](IntegratorConfig& c) { c.rtol = std::nan(""); }, "rtol"},
        ConfigCase{"ZeroAtolScale", [](IntegratorConfig& c) { c.atol_scale = 0.0; }, "atol_scale"},
        ConfigCase{"ZeroSteps", [](IntegratorConfig& c) { c.max_num_steps = 0; }, "max_num_steps"},
        ConfigCase{"EtaFixedStepOfOne", [](IntegratorConfig& c) { c.tuning.eta_max_fixed_step = 1.0; },
                   "tuning.eta_max_fixed_step"},
        ConfigCase{"NegativeSubsteps", [](IntegratorConfig& c) { c.output_substeps = -1; },
                   "output_substeps"},
        ConfigCase{"TooManySubsteps", [](IntegratorConfig& c) { c.output_substeps = 1001; },
                   "output_substeps"}),
    [](const testing::TestParamInfo<ConfigCase>& info) { return info.param.name; });

// Tests that MakeIntegrator builds the integrator the method names and validates the config.
TEST(MakeIntegrator, PicksTheMethod) {
  const LinearPlant plant = BuildPlant(MachineConfig{});
  IntegratorConfig config;
  config.method = IntegratorMethod::kExact;
  auto exact = MakeIntegrator(plant, config, 0.001, 2, 1.0);
  EXPECT_NE(dynamic_cast<ExactIntegrator*>(exact.get()), nullptr);
  config.method = IntegratorMethod::kCvode;
  auto cvode = MakeIntegrator(plant, config, 0.001, 2, 1.0);
  EXPECT_NE(dynamic_cast<CvodeIntegrator*>(cvode.get()), nullptr);
  config.rtol = -1.0;
  EXPECT_THROW(MakeIntegrator(plant, config, 0.001, 2, 1.0), ValidationError);
}

}  // namespace
}  // namespace shapebench::model
