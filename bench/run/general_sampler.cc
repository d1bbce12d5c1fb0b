#include "bench/run/plant_sampler.h"

#include <algorithm>
#include <cmath>

#include "controller/stroke_end.h"

// The general sampler: every output of every substep into the tally (and the trace).
namespace shapebench::bench {
namespace {

void ReserveTrace(Trace* trace, std::size_t expected) {
  trace->time_s.reserve(expected);
  trace->command_position_m.reserve(expected);
  trace->command_velocity_m_s.reserve(expected);
  trace->command_accel_m_s2.reserve(expected);
  trace->deflection_m.reserve(expected);
  trace->command_m.reserve(expected);
  trace->actual_m.reserve(expected);
  trace->deflection_axes_m.reserve(expected);
  trace->block.reserve(expected);
  trace->planned_feed_mm_min.reserve(expected);
}

}  // namespace

// The trace's first sample, at rest at t = 0, and room for the rest: every run simulates
// the motion and the residual window; most settle a period later (reserved up to a few
// million samples; a longer trace grows as it goes).
void PlantSampler::StartTrace() {
  const std::size_t expected = std::min<std::size_t>(
      std::min(window_.max_ticks, window_.window_end() + window_.period_ticks) * substeps_ + 1, 4'000'000);
  ReserveTrace(&result_.trace, expected);
  Record(0.0, samples_.positions.front(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
         Eigen::Vector3d::Zero(), samples_.positions.front(),
         plan_.command.block.empty() ? -1 : plan_.command.block.front());
}

template <RunPhase P>
void PlantSampler::SampleGeneral(std::size_t k, TickTally* tick) {
  const bool commanded = k <= samples_.n;
  const Eigen::Vector3d& a = samples_.AccelAt(k);
  const Eigen::Vector3d& v0 = commanded ? samples_.velocity[k - 1] : samples_.accel[0];
  const Eigen::Vector3d& p0 = commanded ? samples_.positions[k - 1] : samples_.positions.back();
  const std::size_t interpolated_ticks = plan_.command.path_position_m.size();
  const int block = k < interpolated_ticks ? plan_.command.block[k] : -1;
  const double path_s =
      plan_.command.path_position_m.empty() ? 0.0 : plan_.command.path_position_m[std::min(k, interpolated_ticks - 1)];
  const double largest_sq = tally_.contour_sq;  // the run's so far (the tick's is merged after it)
  contour_gauge_.MoveTo(k);
  // Past the arcs (glitch windows) the path position has left, by more than any rounding
  // of it at a stop (the conditions below are then false for them).
  constexpr double kPassedM = 1e-9;
  while (next_arc_ < arcs_.size() &&
         path_s - arcs_[next_arc_].arc->start_s_m > 0.75 * arcs_[next_arc_].arc->length_m + kPassedM) {
    ++next_arc_;
  }
  while (next_glitch_ < glitches_.size() && path_s > glitches_[next_glitch_].arc->end_s_m() + kPassedM) ++next_glitch_;
  for (int j = 0; j < substeps_; ++j) {
    const double* out = outputs_.data() + static_cast<std::ptrdiff_t>(j) * rows_;
    const double tau = plan_.taus_s[j];
    const Eigen::Vector3d p = p0 + v0 * tau + 0.5 * a * tau * tau;
    const Eigen::Vector3d deflection(out[model::kDeflectionRow], out[model::kDeflectionRow + 1],
                                     out[model::kDeflectionRow + 2]);
    const Eigen::Vector3d actual =
        p + Eigen::Vector3d(out[model::kToolErrorRow], out[model::kToolErrorRow + 1], out[model::kToolErrorRow + 2]);
    if (plan_.record_trace) {
      const Eigen::Vector3d v = v0 + a * tau;
      travelled_m_ += v.norm() * dt_ / substeps_;
      const long count = static_cast<long>((k - 1) * substeps_) + j + 1;
      Record(dt_ * static_cast<double>(count) / substeps_, p, v, a, deflection, actual, block);
    }
    peak_axes_ = peak_axes_.cwiseMax(deflection.cwiseAbs());
    if (plan_.has_stroke) overshoot_ = std::max(overshoot_, controller::StrokeOvershoot(p, plan_.scenario.machine.stroke_m));
    for (std::size_t i = next_glitch_; i < glitches_.size() && glitches_[i].arc->start_s_m <= path_s; ++i) {
      glitches_[i].Add(path_s, actual);
    }
    for (std::size_t i = next_arc_; i < arcs_.size() && arcs_[i].arc->start_s_m <= path_s; ++i) {
      ArcWindow& w = arcs_[i];
      const double from_start = path_s - w.arc->start_s_m;
      if (from_start >= 0.25 * w.arc->length_m && from_start <= 0.75 * w.arc->length_m) {
        w.sum_radius_m += std::hypot(actual(w.arc->axis0) - w.arc->center_m(w.arc->axis0),
                                     actual(w.arc->axis1) - w.arc->center_m(w.arc->axis1));
        ++w.samples;
      }
    }
    tick->Add<P>(j, std::abs(plan_.view.Of(deflection)), contour_gauge_.SquaredDistanceTo(actual, largest_sq));
  }
}

template void PlantSampler::SampleGeneral<RunPhase::kMotion>(std::size_t, TickTally*);
template void PlantSampler::SampleGeneral<RunPhase::kWindow>(std::size_t, TickTally*);
template void PlantSampler::SampleGeneral<RunPhase::kTail>(std::size_t, TickTally*);

void PlantSampler::Record(double t, const Eigen::Vector3d& p, const Eigen::Vector3d& v,
                          const Eigen::Vector3d& a, const Eigen::Vector3d& deflection,
                          const Eigen::Vector3d& actual, int block) {
  Trace& trace = result_.trace;
  trace.time_s.push_back(t);
  trace.command_position_m.push_back(plan_.view.magnitude ? travelled_m_ : plan_.view.Of(p));
  trace.command_velocity_m_s.push_back(plan_.view.Of(v));
  trace.command_accel_m_s2.push_back(plan_.view.Of(a));
  trace.deflection_m.push_back(plan_.view.Of(deflection));
  trace.command_m.push_back(p);
  trace.actual_m.push_back(actual);
  trace.deflection_axes_m.push_back(deflection);
  trace.block.push_back(block);
  trace.planned_feed_mm_min.push_back(
      block >= 0 ? plan_.command.block_feed_m_s[static_cast<std::size_t>(block)] * 60000.0 : 0.0);
}

}  // namespace shapebench::bench
