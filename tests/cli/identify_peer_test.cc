// `shapebench identify` against a peer on real FRFs: pyuff's measured beam
// (tests/data/uff/pyuff_beam_accelerance.uff) and sdypy-EMA's modes of it in three bands
// (tests/data/uff/real/, run once with its commit and settings written in each fixture).
// Both fit errors are computed here by shapebench's formula, 100 ||H_fit - H|| / ||H|| over
// the band's lines of every record, each from its own synthesis (modes and residuals).
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/measured/uff58_reader.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace identify_peer_test {
namespace {

using cd = std::complex<double>;
using testing::CliResult;
using testing::RunCli;
using testing::ScratchDir;

const double kPi = 3.14159265358979323846;
const cd kJ(0.0, 1.0);

std::string Source(const std::string& path) { return std::string(SHAPEBENCH_SOURCE_DIR) + "/" + path; }
std::string BeamFile() { return Source("tests/data/uff/pyuff_beam_accelerance.uff"); }
std::string HammerFile() { return Source("tests/data/uff/real/pyfrf_hammer_h1_accelerance.uff"); }
nlohmann::json Peer(const std::string& name) {
  return nlohmann::json::parse(testing::ReadText(Source("tests/data/uff/real/" + name)));
}
cd Complex(const nlohmann::json& v) { return {v["re"].get<double>(), v["im"].get<double>()}; }

// One record's synthesis at w (rad/s), given the record's index.
using Synthesis = std::function<cd(std::size_t, double)>;

// 100 ||H_fit - H|| / ||H|| over the lines lo <= f <= hi Hz of every record.
double FitErrorPercent(const Uff58File& data, double lo, double hi, const Synthesis& fit) {
  double residual = 0.0, norm = 0.0;
  for (std::size_t k = 0; k < data.records.size(); ++k) {
    const Uff58Record& record = data.records[k];
    for (std::size_t i = 0; i < record.values.size(); ++i) {
      const double f = record.frequency_hz[i];
      if (f < lo || f > hi) continue;
      residual += std::norm(fit(k, 2.0 * kPi * f) - record.values[i]);
      norm += std::norm(record.values[i]);
    }
  }
  return 100.0 * std::sqrt(residual / norm);
}

// The pole pair's accelerance term (jw)^2 [A / (jw - l) + conj(A) / (jw - conj(l))].
cd PairTerm(cd a, cd pole, double w) {
  const cd jw = kJ * w;
  return jw * jw * (a / (jw - pole) + std::conj(a) / (jw - std::conj(pole)));
}

// The peer's synthesis (its fixture's `synthesis`): complex residuals LR - w^2 UR.
Synthesis PeerSynthesis(const nlohmann::json& peer) {
  return [&peer](std::size_t k, double w) {
    cd h = Complex(peer["lower_residual"][k]) - w * w * Complex(peer["upper_residual"][k]);
    for (const auto& mode : peer["modes"]) h += PairTerm(Complex(mode["modal_constants"][k]), Complex(mode["pole_rad_per_s"]), w);
    return h;
  };
}

cd Pole(const nlohmann::json& mode) {
  const double wn = 2.0 * kPi * mode["frequency_hz"].get<double>(), zeta = mode["damping_ratio"].get<double>();
  return {-zeta * wn, wn * std::sqrt(1.0 - zeta * zeta)};
}

// shapebench's synthesis (docs/measured-data.md, LSFD): R_r = 2 j w_d A_r, real residuals,
// (jw)^2 [sum (A/(jw - l) + conj) - LR / w^2 + UR].
Synthesis OwnSynthesis(const nlohmann::json& own) {
  return [&own](std::size_t k, double w) {
    const auto& record = own["records"][k];
    cd h = record["lower_residual"].get<double>() - w * w * record["upper_residual"].get<double>();
    for (const auto& mode : own["modes"]) {
      const cd pole = Pole(mode);
      h += PairTerm(Complex(mode["modal_constants"][k]) / (2.0 * kJ * pole.imag()), pole, w);
    }
    return h;
  };
}

// The fit error of the modes' poles with modal constants and real residuals refitted by
// linear least squares on the band (the test's own LSFD), leaving out mode `skip`.
double RefitErrorPercent(const Uff58File& data, double lo, double hi, const nlohmann::json& modes, std::size_t skip) {
  std::vector<cd> poles;
  for (std::size_t r = 0; r < modes.size(); ++r)
    if (r != skip) poles.push_back(Pole(modes[r]));
  std::vector<Eigen::VectorXd> coefficients;
  for (const Uff58Record& record : data.records) {
    std::vector<double> w;
    std::vector<cd> h;
    for (std::size_t i = 0; i < record.values.size(); ++i)
      if (record.frequency_hz[i] >= lo && record.frequency_hz[i] <= hi) {
        w.push_back(2.0 * kPi * record.frequency_hz[i]);
        h.push_back(record.values[i]);
      }
    const Eigen::Index n = static_cast<Eigen::Index>(w.size()), m = static_cast<Eigen::Index>(2 * poles.size() + 2);
    Eigen::MatrixXcd basis(n, m);
    for (Eigen::Index i = 0; i < n; ++i) {
      for (std::size_t r = 0; r < poles.size(); ++r) {
        basis(i, 2 * r) = PairTerm(1.0, poles[r], w[i]);   // Re A
        basis(i, 2 * r + 1) = PairTerm(kJ, poles[r], w[i]);  // Im A
      }
      basis(i, m - 2) = 1.0;            // LR
      basis(i, m - 1) = -w[i] * w[i];   // UR
    }
    Eigen::MatrixXd a(2 * n, m);
    Eigen::VectorXd b(2 * n);
    for (Eigen::Index i = 0; i < n; ++i) {
      a.row(i) = basis.row(i).real();
      a.row(n + i) = basis.row(i).imag();
      b(i) = h[i].real();
      b(n + i) = h[i].imag();
    }
    const Eigen::VectorXd scale = a.colwise().norm().cwiseInverse();
    coefficients.push_back(scale.asDiagonal() * (a * scale.asDiagonal()).colPivHouseholderQr().solve(b));
  }
  return FitErrorPercent(data, lo, hi, [&](std::size_t k, double w) {
    const Eigen::VectorXd& c = coefficients[k];
    cd fit = c(c.size() - 2) - w * w * c(c.size() - 1);
    for (std::size_t r = 0; r < poles.size(); ++r) fit += PairTerm(cd(c(2 * r), c(2 * r + 1)), poles[r], w);
    return fit;
  });
}

// Runs identify (on the peer's band when `band`), exit 0, and returns its JSON.
nlohmann::json Identify(const nlohmann::json& peer, bool band, const std::string& file = BeamFile()) {
  ScratchDir dir;
  std::vector<std::string> args = {"identify", file, "--json", "--out", "out"};
  if (band) {
    args.push_back("--band");
    args.push_back(std::to_string(peer["band_hz"][0].get<int>()) + ":" + std::to_string(peer["band_hz"][1].get<int>()));
  }
  const CliResult result = RunCli(args, dir.path().string());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return nlohmann::json::parse(result.out);
}

// Every peer mode has a mode of identify within 0.5 % in frequency (and, unless the peer's
// frequency is in `damping_exempt_hz`, 25 % in damping), and (unless `others`) identify has
// no other mode.
void ExpectPeerModes(const nlohmann::json& peer, const nlohmann::json& own, const std::vector<double>& damping_exempt_hz = {},
                     bool others = false) {
  if (!others) ASSERT_EQ(own["modes"].size(), peer["modes"].size()) << own.dump(1);
  for (const auto& mode : peer["modes"]) {
    const double f = mode["frequency_hz"].get<double>(), zeta = mode["damping_ratio"].get<double>();
    const auto nearest = std::min_element(own["modes"].begin(), own["modes"].end(), [f](const auto& a, const auto& b) {
      return std::abs(a["frequency_hz"].template get<double>() - f) < std::abs(b["frequency_hz"].template get<double>() - f);
    });
    EXPECT_NEAR((*nearest)["frequency_hz"].get<double>(), f, 0.005 * f);
    const bool exempt = std::any_of(damping_exempt_hz.begin(), damping_exempt_hz.end(),
                                    [f](double e) { return std::abs(e - f) < 0.005 * f; });
    if (!exempt) {
      EXPECT_NEAR((*nearest)["damping_ratio"].get<double>(), zeta, 0.25 * zeta) << f << " Hz";
    }
  }
}

// The fit errors of both, computed here: the peer's synthesis reproduces its fixture's
// fit error on its lines, shapebench's its JSON's; shapebench's is no worse than the peer's + 2 points;
// each mode of shapebench explains at least 1 % of the data's norm (removing it and
// refitting the rest raises the fit error by 1 point or more).
void ExpectFits(const nlohmann::json& peer, const nlohmann::json& own, const std::string& file = BeamFile()) {
  const Uff58File data = ReadUff58(file);
  const double lo = peer["band_hz"][0].get<double>(), hi = peer["band_hz"][1].get<double>();
  // The peer fitted the lines below `hi` (its fixture's fit_error_formula); compared on
  // identify's lines, which take `hi` too.
  EXPECT_NEAR(FitErrorPercent(data, lo, hi - 1.0, PeerSynthesis(peer)), peer["fit_error_percent"].get<double>(), 1e-6);
  const double peer_fit = FitErrorPercent(data, lo, hi, PeerSynthesis(peer));
  const double own_fit = FitErrorPercent(data, lo, hi, OwnSynthesis(own));
  EXPECT_NEAR(own_fit, own["fit_error_percent"].get<double>(), 1e-3);
  EXPECT_LE(own_fit, peer_fit + 2.0);
  const double all = RefitErrorPercent(data, lo, hi, own["modes"], own["modes"].size());
  EXPECT_LE(all, own_fit + 1e-6);  // the linear refit is the optimum for these poles
  for (std::size_t r = 0; r < own["modes"].size(); ++r)
    EXPECT_GE(RefitErrorPercent(data, lo, hi, own["modes"], r) - all, 1.0) << own["modes"][r].dump();
}

// Tests that identify on 30-200 Hz finds the peer's two modes (0.5 % in frequency, 25 % in
// damping), no other, and fits no worse than the peer + 2 points.
TEST(IdentifyPeer, BeamLowBand) {
  const nlohmann::json peer = Peer("sdypy_ema_beam_30_200_hz.json");
  const nlohmann::json own = Identify(peer, true);
  ExpectPeerModes(peer, own);
  ExpectFits(peer, own);
}

// Tests that identify on 400-750 Hz finds the peer's two modes, no other, and fits no worse
// than the peer + 2 points.
TEST(IdentifyPeer, BeamMiddleBand) {
  const nlohmann::json peer = Peer("sdypy_ema_beam_400_750_hz.json");
  const nlohmann::json own = Identify(peer, true);
  ExpectPeerModes(peer, own);
  ExpectFits(peer, own);
}

// Tests that identify on 30-990 Hz finds the peer's six modes in frequency and damping
// (the 51.5 Hz mode's too: its peak is narrower than a line, its damping now fitted on its
// neighbourhood; it was 0.000282 against the peer's 0.000543), no other, and fits no worse
// than the peer + 2 points.
TEST(IdentifyPeer, BeamWholeBand) {
  const nlohmann::json peer = Peer("sdypy_ema_beam_30_990_hz.json");
  const nlohmann::json own = Identify(peer, true);
  ExpectPeerModes(peer, own);
  ExpectFits(peer, own);
  for (const auto& mode : own["modes"]) {
    EXPECT_NE(mode["kept"].get<std::string>().find("narrower than a line"), std::string::npos) << mode.dump();
  }
}

// Tests why the whole band alone cannot fix the 51.5 Hz damping: with the peer's six poles
// and the test's own LSFD, its fit error at 0.000282 and at the peer's 0.000543 differ by
// under 0.01 points, while on the mode's neighbourhood (30-97 Hz) the peer's fits better
// by more than half a point.
TEST(IdentifyPeer, BeamLowModeDampingIsSeenOnlyByItsNeighbourhood) {
  const Uff58File data = ReadUff58(BeamFile());
  nlohmann::json modes = Peer("sdypy_ema_beam_30_990_hz.json")["modes"];
  const auto error_at = [&](double zeta, double lo, double hi) {
    modes[0]["damping_ratio"] = zeta;
    nlohmann::json inside = nlohmann::json::array();
    for (const auto& mode : modes) {
      if (mode["frequency_hz"].get<double>() >= lo && mode["frequency_hz"].get<double>() <= hi) inside.push_back(mode);
    }
    return RefitErrorPercent(data, lo, hi, inside, inside.size());
  };
  EXPECT_LT(std::abs(error_at(0.000282, 30.0, 990.0) - error_at(0.000543, 30.0, 990.0)), 0.01);
  EXPECT_GT(error_at(0.000282, 30.0, 97.0) - error_at(0.000543, 30.0, 97.0), 0.5);
}

// Tests that with neither band nor order given (--band auto --max-order auto) identify
// spans the beam's six peaks (from half the lowest to the file's last line), settles its
// order, and finds the peer's six modes (30-990 Hz fixture) within 0.5 % in frequency and
// 25 % in damping, no other, with a fit error over the peer's lines no worse than its + 2 points.
TEST(IdentifyPeer, BeamAutoBandAndOrder) {
  const nlohmann::json peer = Peer("sdypy_ema_beam_30_990_hz.json");
  ScratchDir dir;
  const CliResult result = RunCli(
      {"identify", BeamFile(), "--band", "auto", "--max-order", "auto", "--json", "--out", "out"}, dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json own = nlohmann::json::parse(result.out);
  ASSERT_EQ(own["auto"]["peaks_hz"].size(), 6u) << own["auto"].dump();
  EXPECT_NEAR(own["auto"]["band_hz"][0].get<double>(), 26.0, 0.5);
  EXPECT_EQ(own["auto"]["band_hz"][1].get<double>(), 1000.0);
  EXPECT_TRUE(own["auto"]["order_settled"].get<bool>());
  ExpectPeerModes(peer, own);
  const Uff58File data = ReadUff58(BeamFile());
  EXPECT_LE(FitErrorPercent(data, 30.0, 989.0, OwnSynthesis(own)),
            FitErrorPercent(data, 30.0, 989.0, PeerSynthesis(peer)) + 2.0);
}

// Tests that the default run on the whole file (no band) finds the modes of the six largest
// peaks within 0.5 % of the peer's frequencies, with exit 0.
TEST(IdentifyPeer, BeamWholeFileDefault) {
  const nlohmann::json peer = Peer("sdypy_ema_beam_30_990_hz.json");
  const nlohmann::json own = Identify(peer, false);
  ASSERT_EQ(own["modes"].size(), 6u) << own.dump(1);
  for (std::size_t r = 0; r < 6; ++r) {
    const double f = peer["modes"][r]["frequency_hz"].get<double>();
    EXPECT_NEAR(own["modes"][r]["frequency_hz"].get<double>(), f, 0.005 * f);
  }
}

// Tests that on the second project's real FRF (pyFRF's hammer test, H1 of five hits, 1 Hz
// lines) identify on 500-3000 Hz finds the peer's four modes (810.5, 851.6, 900.1, 2640.1
// Hz) within 0.5 % in frequency and 25 % in damping, that each of its modes, the peer's and
// any other, explains at least 1 % of the data's norm (removing it and refitting the rest
// raises the fit error by 1 point or more: issue 34's measure of an extra mode), and that
// it fits no worse than the peer + 2 points.
TEST(IdentifyPeer, HammerBand500To3000) {
  const nlohmann::json peer = Peer("sdypy_ema_pyfrf_hammer_500_3000_hz.json");
  const nlohmann::json own = Identify(peer, true, HammerFile());
  ExpectPeerModes(peer, own, {}, true);
  ExpectFits(peer, own, HammerFile());
  // The 2629 Hz pole the diagram missed explains 0.54 points only: dropped, and said why.
  ASSERT_EQ(own["rejected"].size(), 1u) << own["rejected"].dump(1);
  EXPECT_NEAR(own["rejected"][0]["frequency_hz"].get<double>(), 2629.0, 1.0);
  EXPECT_NE(own["rejected"][0]["why"].get<std::string>().find("removing it raises the fit error by 0.5"),
            std::string::npos);
}

// The frequencies of the `count` largest peaks of |H| (a line the largest of the 10 lines
// either side), largest first.
std::vector<double> LargestPeaksHz(const Uff58Record& record, std::size_t count) {
  std::vector<std::pair<double, double>> peaks;  // |H|, Hz
  const std::size_t n = record.values.size();
  for (std::size_t i = 10; i + 10 < n; ++i) {
    bool largest = std::isfinite(std::abs(record.values[i]));
    for (std::size_t j = i - 10; j <= i + 10 && largest; ++j) {
      largest = j == i || !(std::abs(record.values[j]) >= std::abs(record.values[i]));
    }
    if (largest) peaks.push_back({std::abs(record.values[i]), record.frequency_hz[i]});
  }
  std::sort(peaks.rbegin(), peaks.rend());
  std::vector<double> hz;
  for (std::size_t i = 0; i < count && i < peaks.size(); ++i) hz.push_back(peaks[i].second);
  return hz;
}

// The identified mode nearest `f` Hz.
double NearestModeHz(const nlohmann::json& own, double f) {
  double nearest = 0.0;
  for (const auto& mode : own["modes"]) {
    const double g = mode["frequency_hz"].get<double>();
    if (std::abs(g - f) < std::abs(nearest - f)) nearest = g;
  }
  return nearest;
}

// Tests that the default run on the hammer test's whole file (0-12.8 kHz, 12,800 lines, no
// band: fitted in sub-bands of about 2,000 lines) exits 0 and finds the peer's four modes of
// 500-3000 Hz (810.5, 851.6, 900.1, 2640.1 Hz) within 0.5 % in frequency, and a mode within
// 0.5 % of each of |H|'s ten largest peaks (computed here: 4128, 3669, 4164, 5969, 4392, 3689,
// 6078, 4094, 900 and 10505 Hz). It ran over 15 minutes before the sub-bands; now about 10 s of CPU.
TEST(IdentifyPeer, HammerWholeFileDefault) {
  ScratchDir dir;
  const CliResult result = RunCli({"identify", HammerFile(), "--json", "--out", "out"}, dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json own = nlohmann::json::parse(result.out);
  EXPECT_GE(own["sub_bands"].size(), 6u) << own["sub_bands"].dump();
  EXPECT_LE(own["fit_error_percent"].get<double>(), 20.0);
  for (const auto& mode : Peer("sdypy_ema_pyfrf_hammer_500_3000_hz.json")["modes"]) {
    const double f = mode["frequency_hz"].get<double>();
    EXPECT_NEAR(NearestModeHz(own, f), f, 0.005 * f);
  }
  const std::vector<double> peaks = LargestPeaksHz(ReadUff58(HammerFile()).records.front(), 10);
  ASSERT_EQ(peaks.size(), 10u);
  for (const double f : {4128.0, 3669.0, 5969.0, 900.0, 10505.0}) {
    EXPECT_TRUE(std::any_of(peaks.begin(), peaks.end(), [f](double p) { return std::abs(p - f) <= 1.0; })) << f << " Hz is not among " << ::testing::PrintToString(peaks);
  }
  for (const double f : peaks) EXPECT_NEAR(NearestModeHz(own, f), f, 0.005 * f) << "peak at " << f << " Hz";
}

}  // namespace
}  // namespace identify_peer_test
}  // namespace shapebench::bench
