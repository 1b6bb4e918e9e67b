// Uses the installed library as a user would: one edge solve and one tracked sweep; prints the outcome.
#include <cmath>
#include <cstdio>

#include "vibrissa/contact/tracker.hpp"
#include "vibrissa/solve/solvers.hpp"

int main() {
  using namespace vibrissa;
  const Whisker w = Whisker::from_parabola(0.040, 12.0, WhiskerProperties{});
  const Solution s = solve_edge(w, Placement(Pose{}), Edge{{0.02, 0.004, 0.0}, {0.0, 0.0, 1.0}});
  TrackerOptions o;
  o.mode = ContactMode::frictional_edge;
  o.mu = 0.3;
  ContactTracker tracker(w, o);
  const EdgeSegment peg = infinite_segment(Edge{{0.02 * std::cos(0.25), 0.02 * std::sin(0.25), 0.0}, {0, 0, 1}});
  int contact_frames = 0;
  for (int k = 0; k <= 60; ++k) {
    Pose pose;
    pose.theta = -0.3 + 0.01 * k;
    contact_frames += tracker.step(Placement(pose), {&peg, 1}).state == ContactState::contact;
  }
  std::printf("status %s, F_T %.6g N, contact frames %d\n", std::string(to_string(s.status)).c_str(),
              s.whisker_frame.FT, contact_frames);
  return s.status == Status::converged && contact_frames > 0 ? 0 : 1;
}
