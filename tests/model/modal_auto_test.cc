// identify's automatic band (model/modal_band.h) and order (IdentificationOptions::
// auto_order), and the damping of peaks narrower than a line (model/modal_local_damping.h),
// against FRFs synthesised here from known modes: the closed form
// -w^2 sum R_r / (w_r^2 - w^2 + 2 j zeta_r w_r w) of a proportionally damped accelerance;
// a wide band's sub-bands (model/modal_subbands.h).
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "common/math_constants.h"
#include "model/modal_band.h"
#include "model/modal_identification.h"
#include "model/integrator.h"
#include "model/modal_local_damping.h"
#include "model/modal_subbands.h"

namespace shapebench::model {
namespace modal_auto_test {
namespace {

using Complex = std::complex<double>;

struct KnownMode {
  double frequency_hz;
  double damping_ratio;
  double constant;  // R_r, 1/kg
};

// Accelerance at the lines `f` with complex Gaussian noise of `noise` x each line's
// magnitude (fixed seed).
std::vector<Complex> KnownAccelerance(const std::vector<KnownMode>& modes, const std::vector<double>& f, double noise,
                                      unsigned seed) {
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal(0.0, noise / std::sqrt(2.0));
  std::vector<Complex> h;
  for (double fk : f) {
    const double w = kTwoPi * fk;
    Complex a = 0.0;
    for (const KnownMode& m : modes) {
      const double wr = kTwoPi * m.frequency_hz;
      a += -w * w * m.constant / Complex(wr * wr - w * w, 2.0 * m.damping_ratio * wr * w);
    }
    h.push_back(a + std::abs(a) * Complex(normal(generator), normal(generator)));
  }
  return h;
}

std::vector<double> Lines(double step_hz, double top_hz) {
  std::vector<double> f;
  for (int k = 0; k * step_hz <= top_hz + 1e-9; ++k) f.push_back(k * step_hz);
  return f;
}

// Tests that the automatic band finds the peaks (within a line of each mode) and spans
// half the lowest to 1.5 x the highest, inside the longest run of finite lines (a NaN at
// 0 Hz and at the top line are left out).
TEST(ModalBand, SpansThePeaksWithAnOctavesMarginInsideTheFiniteLines) {
  const std::vector<KnownMode> modes = {{20.0, 0.02, 1e-3}, {55.0, 0.015, 5e-4}, {130.0, 0.01, 2e-4}};
  const std::vector<double> f = Lines(0.25, 400.0);
  std::vector<Complex> h = KnownAccelerance(modes, f, 0.01, 34);
  h.front() = h.back() = Complex(std::numeric_limits<double>::quiet_NaN(), 0.0);
  const AutoBand band = ChooseBand(f, {h});
  ASSERT_EQ(band.peaks_hz.size(), 3u);
  for (std::size_t r = 0; r < 3; ++r) EXPECT_NEAR(band.peaks_hz[r], modes[r].frequency_hz, 0.25);
  EXPECT_NEAR(band.min_frequency_hz, 0.5 * band.peaks_hz.front(), 1e-9);
  EXPECT_NEAR(band.max_frequency_hz, 1.5 * band.peaks_hz.back(), 1e-9);
  EXPECT_EQ(band.run_min_hz, 0.25);
  EXPECT_EQ(band.run_max_hz, 399.75);
}

// Tests that a flat FRF (no peak) gets every finite line as its band, and that fewer than
// 4 finite lines in a row are refused.
TEST(ModalBand, WithoutAPeakIsEveryFiniteLine) {
  const std::vector<double> f = Lines(1.0, 100.0);
  const AutoBand band = ChooseBand(f, {std::vector<Complex>(f.size(), Complex(1.0, 0.5))});
  EXPECT_TRUE(band.peaks_hz.empty());
  EXPECT_EQ(band.min_frequency_hz, 1.0);
  EXPECT_EQ(band.max_frequency_hz, 100.0);
  std::vector<Complex> holes(f.size(), Complex(std::numeric_limits<double>::infinity(), 0.0));
  holes[10] = holes[11] = holes[12] = 1.0;
  EXPECT_THROW(ChooseBand(f, {holes}), std::exception);
}

// Seeded synthetic accelerances: 2-6 modes spread over 8-400 Hz (at least 12 % apart),
// damping 0.5-3 %, constants of either sign over a decade, 1 % complex noise, 0.25 Hz lines.
std::vector<KnownMode> SeededModes(unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_int_distribution<int> count(2, 6);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<KnownMode> modes;
  const int n = count(generator);
  double f = 8.0 * (1.0 + unit(generator));
  for (int r = 0; r < n; ++r) {
    const double sign = unit(generator) < 0.3 ? -1.0 : 1.0;
    modes.push_back({f, 0.005 + 0.025 * unit(generator), sign * 1e-3 * std::pow(10.0, -unit(generator))});
    f *= 1.12 + 0.5 * unit(generator);
    if (f > 400.0) break;
  }
  return modes;
}

// Tests that with neither band nor order given the seeded synthetic FRFs' modes are found,
// each within 0.5 % in frequency and 15 % in damping, and no other, with the order settled
// by the stabilisation criterion (the modes picked up to one order repeat at twice it).
TEST(ModalAutoOrder, FindsTheKnownModesOfSeededFrfs) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const std::vector<KnownMode> modes = SeededModes(seed);
    const std::vector<double> f = Lines(0.25, 600.0);
    const std::vector<std::vector<Complex>> h = {KnownAccelerance(modes, f, 0.01, 100 + seed)};
    const AutoBand band = ChooseBand(f, h);
    IdentificationOptions options;
    options.min_frequency_hz = band.min_frequency_hz;
    options.max_frequency_hz = band.max_frequency_hz;
    options.auto_order = true;
    options.max_order = 200;
    const ModalIdentification result = IdentifyModes(f, h, 2, options);
    EXPECT_EQ(result.order_stop, "settled") << "seed " << seed;
    ASSERT_GE(result.orders_compared.size(), 2u);
    EXPECT_EQ(result.orders_compared.front(), kFirstAutoOrder);
    EXPECT_EQ(result.max_order, result.orders_compared.back());
    ASSERT_EQ(result.modes.size(), modes.size()) << "seed " << seed;
    for (std::size_t r = 0; r < modes.size(); ++r) {
      EXPECT_NEAR(result.modes[r].frequency_hz, modes[r].frequency_hz, 0.005 * modes[r].frequency_hz) << seed;
      EXPECT_NEAR(result.modes[r].damping_ratio, modes[r].damping_ratio, 0.15 * modes[r].damping_ratio) << seed;
    }
  }
}

// Tests that a peak narrower than a line (51.5 Hz at 0.05 %, 1 Hz lines) beside a much
// larger accelerance peak gets its damping back from its neighbourhood (within 5 %) when
// started at half of it, its frequency kept, while a peak the lines resolve is left alone.
TEST(ModalLocalDamping, NarrowPeakDampingComesFromItsNeighbourhood) {
  const std::vector<KnownMode> modes = {{51.5, 0.0005, 2e-4}, {300.0, 0.02, 5e-5}, {958.5, 0.00014, 3e-5}};
  const std::vector<double> f = Lines(1.0, 1000.0);
  std::vector<double> x;
  std::vector<std::vector<Complex>> data(1);
  const std::vector<Complex> h = KnownAccelerance(modes, f, 0.0, 1);
  for (std::size_t k = 30; k < f.size(); ++k) x.push_back(f[k] / f.back()), data[0].push_back(h[k]);
  ModalModel model;
  const double started[3] = {0.00025, 0.02, 0.00014};
  for (std::size_t r = 0; r < 3; ++r) {
    const double wn = modes[r].frequency_hz / f.back();
    model.poles.push_back({-started[r] * wn, wn * std::sqrt(1.0 - started[r] * started[r])});
  }
  FitLinear(x, data, 2, &model);
  const std::vector<bool> local = LocalDampingOfNarrowPeaks(x, data, 2, 0.5, 0.02, &model);
  EXPECT_EQ(local, (std::vector<bool>{true, false, true}));
  EXPECT_NEAR(-model.poles[0].real() / std::abs(model.poles[0]), 0.0005, 0.05 * 0.0005);
  EXPECT_NEAR(std::abs(model.poles[0]), 51.5 / f.back(), 1e-12);
  EXPECT_NEAR(-model.poles[1].real() / std::abs(model.poles[1]), 0.02, 1e-15);
}

// Tests that a band of more than kMaxLinesPerFit lines (6,000 lines, six modes 500-5300 Hz,
// 1 % noise) is fitted in sub-bands of at most about kSubBandLines lines, cut between the
// peaks (no cut within 5 % of a mode), that every mode is found within 0.5 % in frequency
// and 15 % in damping and no other, that the charged work is counted and within the
// budget, and that a budget below it stops the fit with WORK_LIMIT.
TEST(ModalSubBands, WideBandIsFittedSubBandBySubBand) {
  const std::vector<KnownMode> modes = {{500.0, 0.01, 2e-4},  {1400.0, 0.008, 1e-4}, {2300.0, 0.01, 1.5e-4},
                                        {3100.0, 0.012, 1e-4}, {4200.0, 0.01, 2e-4}, {5300.0, 0.009, 1e-4}};
  const std::vector<double> f = Lines(1.0, 6000.0);
  const std::vector<std::vector<Complex>> h = {KnownAccelerance(modes, f, 0.01, 7)};
  IdentificationOptions options;
  options.min_frequency_hz = 1.0;
  const ModalIdentification result = IdentifyModes(f, h, 2, options);
  ASSERT_EQ(result.sub_band_edges_hz.size(), 4u);  // 6,000 lines: 3 sub-bands
  ASSERT_EQ(result.sub_band_orders.size(), 3u);
  for (std::size_t i = 0; i + 1 < result.sub_band_edges_hz.size(); ++i) {
    EXPECT_LE(result.sub_band_edges_hz[i + 1] - result.sub_band_edges_hz[i], 1.25 * kSubBandLines);
    for (const KnownMode& mode : modes) {
      EXPECT_GT(std::abs(result.sub_band_edges_hz[i] - mode.frequency_hz), 0.05 * mode.frequency_hz);
    }
  }
  ASSERT_EQ(result.modes.size(), modes.size());
  for (std::size_t r = 0; r < modes.size(); ++r) {
    EXPECT_NEAR(result.modes[r].frequency_hz, modes[r].frequency_hz, 0.005 * modes[r].frequency_hz);
    EXPECT_NEAR(result.modes[r].damping_ratio, modes[r].damping_ratio, 0.15 * modes[r].damping_ratio);
  }
  EXPECT_GT(result.work, 0.0);
  EXPECT_LE(result.work, options.max_work);
  options.max_work = 0.5 * result.work;
  try {
    IdentifyModes(f, h, 2, options);
    ADD_FAILURE() << "no WORK_LIMIT";
  } catch (const SolverError& error) {
    EXPECT_EQ(error.flag_name(), "WORK_LIMIT");
  }
}

// Tests that a sub-band's mode within two lines of an inner edge is left out, one at the
// band's ends or farther from the edges kept.
TEST(ModalSubBands, ModeAtAnInnerEdgeIsLeftOut) {
  const std::vector<double> edges = {1.0, 2000.0, 4000.0, 6000.0};
  EXPECT_TRUE(NearInnerEdge(2001.5, edges, 1.0));
  EXPECT_TRUE(NearInnerEdge(3998.0, edges, 1.0));
  EXPECT_FALSE(NearInnerEdge(2003.0, edges, 1.0));
  EXPECT_FALSE(NearInnerEdge(5999.0, edges, 1.0));
  EXPECT_FALSE(NearInnerEdge(1.0, edges, 1.0));
}

}  // namespace
}  // namespace modal_auto_test
}  // namespace shapebench::model
