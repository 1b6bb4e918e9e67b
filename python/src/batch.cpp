// Batch solves: many frames and/or many whiskers in one call, the GIL released and OpenMP across cores.
//
// Layout. Per-frame inputs have shape (F, 3) (or (F,) for scalars) for one series of F frames, or
// (S, F, 3) / (S, F) for S independent series; `whisker` is one Whisker (shared by every series) or a
// sequence of S whiskers. Anything without a series axis is shared by all series; a (3,) vector or a scalar
// is shared by all frames. Results are stacked with shape (F, ...) or, when any input has a series axis,
// (S, F, ...).
//
// Parallelism. With warm starts (the default) frame k of a series starts from frame k-1's solution, so a
// series runs sequentially and series run in parallel. Without warm starts every frame is independent and
// frames run in parallel. Results do not depend on the number of threads.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include <omp.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "interruptible.hpp"
#include "vibrissa/contact/tracker.hpp"
#include "vibrissa/solve/solvers.hpp"

namespace vibrissa::python {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// One broadcastable per-frame input: element (s, f) lives at data + s*stride_s + f*stride_f.
struct Field {
  const char* name = "";
  DoubleArray array;  // keeps the converted data alive
  const double* data = nullptr;
  py::ssize_t series = -1;  // -1: no series axis
  py::ssize_t frames = -1;  // -1: no frame axis
  py::ssize_t stride_s = 0, stride_f = 0;
  [[nodiscard]] bool present() const { return data != nullptr; }
  [[nodiscard]] const double* at(py::ssize_t s, py::ssize_t f) const { return data + s * stride_s + f * stride_f; }
  [[nodiscard]] Eigen::Vector3d vec(py::ssize_t s, py::ssize_t f) const {
    const double* p = at(s, f);
    return {p[0], p[1], p[2]};
  }
  [[nodiscard]] double scalar(py::ssize_t s, py::ssize_t f) const { return *at(s, f); }
};

/// A vector input: (3,), (F, 3) or (S, F, 3).
Field vector_field(const py::object& obj, const char* name) {
  Field fd;
  fd.name = name;
  if (obj.is_none()) return fd;
  fd.array = as_double_array(obj, name);
  const DoubleArray& a = fd.array;
  const py::ssize_t nd = a.ndim();
  if (nd < 1 || nd > 3 || a.shape(nd - 1) != 3)
    throw py::value_error(std::string(name) + " must have shape (3,), (F, 3) or (S, F, 3), got " + shape_string(a));
  fd.data = a.data();
  if (nd >= 2) {
    fd.frames = a.shape(nd - 2);
    fd.stride_f = 3;
  }
  if (nd == 3) {
    fd.series = a.shape(0);
    fd.stride_s = 3 * a.shape(1);
  }
  return fd;
}

/// A scalar input: a number, (F,) or (S, F).
Field scalar_field(const py::object& obj, const char* name) {
  Field fd;
  fd.name = name;
  if (obj.is_none()) return fd;
  fd.array = as_double_array(obj, name);
  const DoubleArray& a = fd.array;
  const py::ssize_t nd = a.ndim();
  if (nd > 2) throw py::value_error(std::string(name) + " must be a number or have shape (F,) or (S, F), got " + shape_string(a));
  fd.data = a.data();
  if (nd >= 1) {
    fd.frames = a.shape(nd - 1);
    fd.stride_f = 1;
  }
  if (nd == 2) {
    fd.series = a.shape(0);
    fd.stride_s = a.shape(1);
  }
  return fd;
}

/// The whiskers of a batch: one shared whisker, or one per series.
struct Whiskers {
  py::object keep_alive;
  std::vector<const Whisker*> list;
  bool per_series = false;
  [[nodiscard]] const Whisker& of(py::ssize_t s) const { return *list[per_series ? static_cast<std::size_t>(s) : 0]; }
};

Whiskers whiskers_arg(const py::object& obj) {
  Whiskers w;
  w.keep_alive = obj;
  if (py::isinstance<Whisker>(obj)) {
    w.list.push_back(&obj.cast<const Whisker&>());
    return w;
  }
  if (py::isinstance<py::sequence>(obj) && !py::isinstance<py::str>(obj)) {
    const py::sequence seq = obj.cast<py::sequence>();
    w.keep_alive = py::tuple(seq);  // a snapshot: the caller may not mutate what we read without the GIL
    const py::tuple items = w.keep_alive.cast<py::tuple>();
    if (items.empty()) throw py::value_error("whisker: the sequence of whiskers is empty");
    for (std::size_t i = 0; i < items.size(); ++i) {
      if (!py::isinstance<Whisker>(items[i]))
        throw py::value_error("whisker[" + std::to_string(i) + "] must be a vibrissa.Whisker, got " +
                              std::string(py::str(py::type::handle_of(items[i]).attr("__name__"))));
      w.list.push_back(&items[i].cast<const Whisker&>());
    }
    w.per_series = true;
    return w;
  }
  throw py::value_error("whisker must be a vibrissa.Whisker or a sequence of them, got " +
                        std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
}

/// Agreed layout of a batch: S series of F frames.
struct Layout {
  py::ssize_t series = 1, frames = 1;
  bool series_axis = false;
};

Layout layout_of(const Whiskers& w, std::initializer_list<const Field*> fields) {
  Layout L;
  const char* frames_from = nullptr;
  const char* series_from = nullptr;
  if (w.per_series) {
    L.series = static_cast<py::ssize_t>(w.list.size());
    L.series_axis = true;
    series_from = "whisker";
  }
  for (const Field* f : fields) {
    if (!f->present()) continue;
    if (f->frames >= 0) {
      if (frames_from && f->frames != L.frames)
        throw py::value_error(std::string(f->name) + " has " + std::to_string(f->frames) + " frames but " + frames_from +
                              " has " + std::to_string(L.frames) + " (shape " + shape_string(f->array) + ")");
      L.frames = f->frames;
      frames_from = f->name;
    }
    if (f->series >= 0) {
      if (series_from && f->series != L.series)
        throw py::value_error(std::string(f->name) + " has " + std::to_string(f->series) + " series but " + series_from +
                              " has " + std::to_string(L.series) + " (shape " + shape_string(f->array) + ")");
      L.series = f->series;
      L.series_axis = true;
      series_from = f->name;
    }
  }
  return L;
}

/// Stacked result arrays, allocated with the GIL held and filled without it.
struct Outputs {
  std::vector<py::ssize_t> prefix;
  py::array_t<std::int32_t> status, iterations;
  py::array_t<double> force_magnitude, arc_length, angle, contact_point, force, moment, wf_force, wf_moment, FT, MB,
      FD, MD, normal_force, edge_force, residual, state, shape;
  bool with_shape = false;
  py::ssize_t nodes = 0;

  template <class T>
  py::array_t<T> make(std::initializer_list<py::ssize_t> tail) const {
    std::vector<py::ssize_t> dims = prefix;
    dims.insert(dims.end(), tail.begin(), tail.end());
    return py::array_t<T>(dims);
  }

  Outputs(const Layout& L, bool shapes, py::ssize_t node_count) : with_shape(shapes), nodes(node_count) {
    if (L.series_axis) prefix.push_back(L.series);
    prefix.push_back(L.frames);
    status = make<std::int32_t>({});
    iterations = make<std::int32_t>({});
    force_magnitude = make<double>({});
    arc_length = make<double>({});
    angle = make<double>({});
    contact_point = make<double>({3});
    force = make<double>({3});
    moment = make<double>({3});
    wf_force = make<double>({3});
    wf_moment = make<double>({3});
    FT = make<double>({});
    MB = make<double>({});
    FD = make<double>({});
    MD = make<double>({});
    normal_force = make<double>({});
    edge_force = make<double>({});
    residual = make<double>({});
    state = make<double>({4});
    if (with_shape) shape = make<double>({nodes, 3});
  }

  /// Raw pointers, taken with the GIL held, so that filling needs no Python API.
  struct Raw {
    std::int32_t *status, *iterations;
    double *force_magnitude, *arc_length, *angle, *contact_point, *force, *moment, *wf_force, *wf_moment, *FT, *MB, *FD,
        *MD, *normal_force, *edge_force, *residual, *state, *shape;
    py::ssize_t nodes;
  };
  Raw raw() {
    return Raw{status.mutable_data(), iterations.mutable_data(), force_magnitude.mutable_data(),
               arc_length.mutable_data(), angle.mutable_data(), contact_point.mutable_data(), force.mutable_data(),
               moment.mutable_data(), wf_force.mutable_data(), wf_moment.mutable_data(), FT.mutable_data(),
               MB.mutable_data(), FD.mutable_data(), MD.mutable_data(), normal_force.mutable_data(),
               edge_force.mutable_data(), residual.mutable_data(), state.mutable_data(),
               with_shape ? shape.mutable_data() : nullptr, nodes};
  }

  py::dict to_dict() const {
    py::dict wf;
    wf["force"] = wf_force;
    wf["moment"] = wf_moment;
    wf["Fx"] = py::object(wf_force[py::make_tuple(py::ellipsis(), 0)]);
    wf["Mx"] = py::object(wf_moment[py::make_tuple(py::ellipsis(), 0)]);
    wf["FT"] = FT;
    wf["MB"] = MB;
    wf["FD"] = FD;
    wf["MD"] = MD;
    py::dict d;
    d["status"] = status;
    d["force_magnitude"] = force_magnitude;
    d["arc_length"] = arc_length;
    d["angle"] = angle;
    d["contact_point_W"] = contact_point;
    d["force_W"] = force;
    d["moment_W"] = moment;
    d["whisker_frame"] = wf;
    d["normal_force"] = normal_force;
    d["edge_force"] = edge_force;
    d["residual"] = residual;
    d["iterations"] = iterations;
    d["state"] = state;
    d["shape_W"] = with_shape ? py::object(shape) : py::object(py::none());
    return d;
  }
};

void store(const Outputs::Raw& r, py::ssize_t i, const Solution& s) {
  auto put3 = [i](double* dst, const Eigen::Vector3d& v) { std::copy(v.data(), v.data() + 3, dst + 3 * i); };
  r.status[i] = static_cast<std::int32_t>(s.status);
  r.iterations[i] = s.iterations;
  r.force_magnitude[i] = s.force_magnitude;
  r.arc_length[i] = s.arc_length;
  r.angle[i] = s.angle;
  put3(r.contact_point, s.contact_point_W);
  put3(r.force, s.force_W);
  put3(r.moment, s.moment_W);
  put3(r.wf_force, s.whisker_frame.force);
  put3(r.wf_moment, s.whisker_frame.moment);
  r.FT[i] = s.whisker_frame.FT;
  r.MB[i] = s.whisker_frame.MB;
  r.FD[i] = s.whisker_frame.FD;
  r.MD[i] = s.whisker_frame.MD;
  r.normal_force[i] = s.normal_force.value_or(kNaN);
  r.edge_force[i] = s.edge_force.value_or(kNaN);
  r.residual[i] = s.residual;
  double* st = r.state + 4 * i;
  st[0] = s.state.force_x;
  st[1] = s.state.force_y;
  st[2] = s.state.force_z;
  st[3] = s.state.arc_length;
  if (r.shape) {
    double* dst = r.shape + 3 * r.nodes * i;
    if (static_cast<py::ssize_t>(s.shape_W.size()) == r.nodes)
      for (std::size_t k = 0; k < s.shape_W.size(); ++k) std::copy(s.shape_W[k].data(), s.shape_W[k].data() + 3, dst + 3 * k);
    else
      std::fill(dst, dst + 3 * r.nodes, kNaN);
  }
}

/// Status code of a frame whose input was refused (one past the C++ Status values; vibrissa.batch's
/// STATUS_NAMES names it "invalid_input"): its numbers are NaN and its message is in the result's "error".
constexpr std::int32_t kInvalidInputStatus = static_cast<std::int32_t>(Status::underdetermined) + 1;

void store_failed(const Outputs::Raw& r, py::ssize_t i) {
  auto nan3 = [i](double* dst) { std::fill(dst + 3 * i, dst + 3 * i + 3, kNaN); };
  r.status[i] = kInvalidInputStatus;
  r.iterations[i] = 0;
  r.force_magnitude[i] = r.arc_length[i] = r.angle[i] = kNaN;
  nan3(r.contact_point), nan3(r.force), nan3(r.moment), nan3(r.wf_force), nan3(r.wf_moment);
  r.FT[i] = r.MB[i] = r.FD[i] = r.MD[i] = r.normal_force[i] = r.edge_force[i] = r.residual[i] = kNaN;
  std::fill(r.state + 4 * i, r.state + 4 * i + 4, kNaN);
  if (r.shape) std::fill(r.shape + 3 * r.nodes * i, r.shape + 3 * r.nodes * (i + 1), kNaN);
}

/// Per-frame placement: the whisker's own placement, overridden by (base, angles) when either is given.
struct Poses {
  Field base, angles;
  [[nodiscard]] Placement at(const Whisker& w, py::ssize_t s, py::ssize_t f) const {
    if (!base.present() && !angles.present()) return w.placement();
    Pose p = w.placement().pose();
    if (base.present()) p.p_W_base = base.vec(s, f);
    if (angles.present()) {
      const Eigen::Vector3d a = angles.vec(s, f);
      p.theta = a.x();
      p.phi = a.y();
      p.zeta = a.z();
    }
    return Placement(p);
  }
};

int thread_count(const py::object& threads) {
  if (threads.is_none()) return omp_get_max_threads();
  return thread_count_arg(threads, 1);
}

/// Runs `solve_one(s, f)` over every (series, frame) of the layout in parallel (independent frames).
/// With `tracked` instead, each series runs in time order through one ContactTracker (contact/tracker.hpp):
/// `frame_input(s, f, X, segment, input)` describes frame f, and the tracker carries warm starts and contact
/// history from frame to frame; series run in parallel.
struct SeriesTracking {
  TrackerOptions options;
  std::function<void(py::ssize_t, py::ssize_t, Placement&, std::optional<EdgeSegment>&, TrackedInput&)> frame_input;
};

template <class SolveOne>
py::dict run_batch(const Layout& L, const Whiskers& ws, const SeriesTracking* tracked, bool shapes,
                   const py::object& threads, const py::object& progress, SolveOne&& solve_one) {
  py::ssize_t nodes = 0;
  if (shapes) {
    nodes = ws.list.front()->links() + 1;
    for (const Whisker* w : ws.list)
      if (w->links() + 1 != nodes)
        throw py::value_error("shapes=True needs whiskers with equal numbers of links, got " +
                              std::to_string(nodes - 1) + " and " + std::to_string(w->links()));
  }
  const int nt = thread_count(threads);
  Outputs out(L, shapes, nodes);
  const Outputs::Raw raw = out.raw();
  const py::ssize_t S = L.series, F = L.frames;
  const py::ssize_t items = tracked ? S : S * F;
  // Every frame is solved: a frame whose solve throws (invalid input) is recorded, NaN with its message, and
  // the batch goes on (a tracked series with its next frame). vibrissa.batch raises the first one for
  // on_error="raise".
  std::vector<std::string> errors(static_cast<std::size_t>(S * F));
  std::vector<unsigned char> error_is_value(errors.size(), 1);
  auto record = [&](py::ssize_t i, const std::exception& e) {
    store_failed(raw, i);
    errors[static_cast<std::size_t>(i)] = e.what();
    error_is_value[static_cast<std::size_t>(i)] = dynamic_cast<const std::invalid_argument*>(&e) != nullptr;
  };
  // On a worker thread with the GIL released; Ctrl-C or an exception from `progress` cancels between frames.
  run_interruptible(
      [&](const RunControl& control) {
        ProgressCounter counter(control, static_cast<std::size_t>(S * F));
        std::atomic<bool> cancelled{false};
#pragma omp parallel for schedule(dynamic, 1) num_threads(nt)
        for (py::ssize_t item = 0; item < items; ++item) {
          try {
            if (tracked) {
              const py::ssize_t s = item;
              ContactTracker tracker(ws.of(s), tracked->options);
              Placement X;
              std::optional<EdgeSegment> segment;
              for (py::ssize_t f = 0; f < F; ++f) {
                counter.check();
                try {
                  TrackedInput input;
                  tracked->frame_input(s, f, X, segment, input);
                  store(raw, s * F + f, tracker.step_tracked(X, segment ? &*segment : nullptr, input).solution);
                } catch (const Cancelled&) {
                  throw;
                } catch (const std::exception& e) {
                  record(s * F + f, e);
                }
                counter.advance();
              }
            } else {
              counter.check();
              try {
                store(raw, item, solve_one(item / F, item % F));
              } catch (const Cancelled&) {
                throw;
              } catch (const std::exception& e) {
                record(item, e);
              }
              counter.advance();
            }
          } catch (const Cancelled&) {
            cancelled = true;
          }
        }
        if (cancelled) throw Cancelled();
        return 0;
      },
      progress);
  py::dict d = out.to_dict();
  py::list messages;
  py::list kinds;
  for (std::size_t i = 0; i < errors.size(); ++i) {
    if (errors[i].empty()) continue;
    const py::ssize_t item = static_cast<py::ssize_t>(i);
    messages.append(py::make_tuple(item / F, item % F, errors[i]));
    kinds.append(error_is_value[i] ? "ValueError" : "RuntimeError");
  }
  d["errors"] = messages;
  d["error_kinds"] = kinds;
  return d;
}

/// The edge of frame (s, f): a point and an optional direction (default world +z).
std::optional<EdgeSegment> edge_at(const Field& points, const Field& directions, py::ssize_t s, py::ssize_t f) {
  Edge e;
  e.point = points.vec(s, f);
  e.direction = directions.present() ? directions.vec(s, f) : Eigen::Vector3d::UnitZ();
  return infinite_segment(e);
}

}  // namespace

void bind_batch(py::module_& m) {
  m.def(
      "solve_force_batch",
      [](const py::object& whisker, const py::object& force, const py::object& arc_length, const py::object& angle,
         const py::object& pose_base, const py::object& pose_angles, const py::object& options, bool shapes,
         const py::object& threads, const py::object& progress) {
        const Whiskers ws = whiskers_arg(whisker);
        const Field fF = scalar_field(force, "force"), fs = scalar_field(arc_length, "arc_length"),
                    fa = scalar_field(angle, "angle");
        Poses poses{vector_field(pose_base, "pose_base"), vector_field(pose_angles, "pose_angles")};
        const Layout L = layout_of(ws, {&fF, &fs, &fa, &poses.base, &poses.angles});
        SolveOptions o = options_arg(options);
        o.compute_shape = shapes;
        return run_batch(L, ws, nullptr, shapes, threads, progress, [&](py::ssize_t s, py::ssize_t f) {
          const Whisker& w = ws.of(s);
          const double ang = fa.present() ? fa.scalar(s, f) : 0.0;
          return solve_force(w, poses.at(w, s, f), fF.scalar(s, f), fs.scalar(s, f), ang, o);
        });
      },
      py::arg("whisker"), py::arg("force"), py::arg("arc_length"), py::arg("angle") = py::none(), py::kw_only(),
      py::arg("pose_base") = py::none(), py::arg("pose_angles") = py::none(), py::arg("options") = py::none(),
      py::arg("shapes") = false, py::arg("threads") = py::none(), py::arg("progress") = py::none());

  m.def(
      "solve_point_batch",
      [](const py::object& whisker, const py::object& points, const py::object& arc_length_hint,
         const py::object& edge_direction, const py::object& pose_base, const py::object& pose_angles,
         const py::object& options, bool warm_start, bool shapes, const py::object& threads,
         const py::object& progress) {
        const Whiskers ws = whiskers_arg(whisker);
        const Field fp = vector_field(points, "points_W");
        if (!fp.present()) throw py::value_error("points_W must be given");
        const Field fh = scalar_field(arc_length_hint, "arc_length_hint");
        const Field fd = vector_field(edge_direction, "edge_direction_W");
        Poses poses{vector_field(pose_base, "pose_base"), vector_field(pose_angles, "pose_angles")};
        const Layout L = layout_of(ws, {&fp, &fh, &fd, &poses.base, &poses.angles});
        SolveOptions o = options_arg(options);
        o.compute_shape = shapes;
        auto hint_at = [&](py::ssize_t s, py::ssize_t f) {
          return fh.present() ? std::optional<double>(fh.scalar(s, f)) : std::nullopt;
        };
        SeriesTracking tracking{TrackerOptions{ContactMode::contact_point, 0.0, o},
                                [&](py::ssize_t s, py::ssize_t f, Placement& X, std::optional<EdgeSegment>& seg,
                                    TrackedInput& in) {
                                  X = poses.at(ws.of(s), s, f);
                                  if (fd.present()) seg = edge_at(fp, fd, s, f);
                                  in.p_W_contact = fp.vec(s, f);
                                  in.arc_length_hint = hint_at(s, f);
                                }};
        return run_batch(L, ws, warm_start ? &tracking : nullptr, shapes, threads, progress,
                         [&](py::ssize_t s, py::ssize_t f) {
          const Whisker& w = ws.of(s);
          const std::optional<Eigen::Vector3d> dir =
              fd.present() ? std::optional<Eigen::Vector3d>(fd.vec(s, f)) : std::nullopt;
          return solve_point(w, poses.at(w, s, f), fp.vec(s, f), hint_at(s, f), o, nullptr, dir);
        });
      },
      py::arg("whisker"), py::arg("points_W"), py::kw_only(), py::arg("arc_length_hint") = py::none(),
      py::arg("edge_direction_W") = py::none(), py::arg("pose_base") = py::none(), py::arg("pose_angles") = py::none(),
      py::arg("options") = py::none(), py::arg("warm_start") = true, py::arg("shapes") = false,
      py::arg("threads") = py::none(), py::arg("progress") = py::none());

  m.def(
      "solve_edge_batch",
      [](const py::object& whisker, const py::object& edge_points, const py::object& edge_directions,
         const py::object& arc_length_hint, const py::object& approach, const py::object& pose_base,
         const py::object& pose_angles, const py::object& options, bool warm_start, bool shapes,
         const py::object& threads, const py::object& progress) {
        const Whiskers ws = whiskers_arg(whisker);
        const Field fp = vector_field(edge_points, "edge_points_W");
        if (!fp.present()) throw py::value_error("edge_points_W must be given");
        const Field fd = vector_field(edge_directions, "edge_directions_W");
        const Field fh = scalar_field(arc_length_hint, "arc_length_hint");
        const Field fa = vector_field(approach, "approach_W");
        Poses poses{vector_field(pose_base, "pose_base"), vector_field(pose_angles, "pose_angles")};
        const Layout L = layout_of(ws, {&fp, &fd, &fh, &fa, &poses.base, &poses.angles});
        SolveOptions o = options_arg(options);
        o.compute_shape = shapes;
        auto hint_at = [&](py::ssize_t s, py::ssize_t f) {
          return fh.present() ? std::optional<double>(fh.scalar(s, f)) : std::nullopt;
        };
        auto approach_at = [&](py::ssize_t s, py::ssize_t f) {
          return fa.present() ? std::optional<Eigen::Vector3d>(fa.vec(s, f)) : std::nullopt;
        };
        SeriesTracking tracking{TrackerOptions{ContactMode::edge, 0.0, o},
                                [&](py::ssize_t s, py::ssize_t f, Placement& X, std::optional<EdgeSegment>& seg,
                                    TrackedInput& in) {
                                  X = poses.at(ws.of(s), s, f);
                                  seg = edge_at(fp, fd, s, f);
                                  in.arc_length_hint = hint_at(s, f);
                                  in.approach_W = approach_at(s, f);
                                }};
        return run_batch(L, ws, warm_start ? &tracking : nullptr, shapes, threads, progress,
                         [&](py::ssize_t s, py::ssize_t f) {
          const Whisker& w = ws.of(s);
          return solve_edge(w, poses.at(w, s, f), edge_at(fp, fd, s, f)->line(), hint_at(s, f), o, nullptr,
                            approach_at(s, f));
        });
      },
      py::arg("whisker"), py::arg("edge_points_W"), py::arg("edge_directions_W") = py::none(), py::kw_only(),
      py::arg("arc_length_hint") = py::none(), py::arg("approach_W") = py::none(), py::arg("pose_base") = py::none(),
      py::arg("pose_angles") = py::none(), py::arg("options") = py::none(), py::arg("warm_start") = true,
      py::arg("shapes") = false, py::arg("threads") = py::none(), py::arg("progress") = py::none());

  m.def(
      "solve_frictional_edge_batch",
      [](const py::object& whisker, const py::object& edge_points, const py::object& edge_directions, double mu,
         const py::object& initial_contact, const py::object& approach, const py::object& pose_base,
         const py::object& pose_angles, const py::object& options, bool shapes, const py::object& threads,
         const py::object& progress) {
        const Whiskers ws = whiskers_arg(whisker);
        const Field fp = vector_field(edge_points, "edge_points_W");
        if (!fp.present()) throw py::value_error("edge_points_W must be given");
        const Field fd = vector_field(edge_directions, "edge_directions_W");
        const Field fa = vector_field(approach, "approach_W");
        // initial_contact_W: (3,) shared by every series, or (S, 3) one per series.
        DoubleArray q0;
        const bool has_q0 = !initial_contact.is_none();
        if (has_q0) {
          q0 = as_double_array(initial_contact, "initial_contact_W");
          if (!((q0.ndim() == 1 && q0.shape(0) == 3) || (q0.ndim() == 2 && q0.shape(1) == 3)))
            throw py::value_error("initial_contact_W must have shape (3,) or (S, 3), got " + shape_string(q0));
        }
        Poses poses{vector_field(pose_base, "pose_base"), vector_field(pose_angles, "pose_angles")};
        const Layout L = layout_of(ws, {&fp, &fd, &fa, &poses.base, &poses.angles});
        SolveOptions o = options_arg(options);
        o.compute_shape = shapes;
        const py::ssize_t rows = has_q0 ? (q0.ndim() == 1 ? 1 : q0.shape(0)) : 0;
        if (has_q0 && rows != 1 && rows != L.series)
          throw py::value_error("initial_contact_W has " + std::to_string(rows) + " rows but the batch has " +
                                std::to_string(L.series) + " series");
        TrackerOptions topt{ContactMode::frictional_edge, mu, o};
        validate(topt);
        SeriesTracking tracking{topt, [&](py::ssize_t s, py::ssize_t f, Placement& X, std::optional<EdgeSegment>& seg,
                                          TrackedInput& in) {
                                  X = poses.at(ws.of(s), s, f);
                                  seg = edge_at(fp, fd, s, f);
                                  if (fa.present()) in.approach_W = fa.vec(s, f);
                                  if (has_q0 && f == 0) {
                                    const double* p = q0.data() + 3 * (rows == 1 ? 0 : s);
                                    in.initial_contact_W = Eigen::Vector3d(p[0], p[1], p[2]);
                                  }
                                }};
        // Contact history lives per series: always tracked, series in parallel.
        return run_batch(L, ws, &tracking, shapes, threads, progress,
                         [](py::ssize_t, py::ssize_t) { return Solution{}; });
      },
      py::arg("whisker"), py::arg("edge_points_W"), py::arg("edge_directions_W") = py::none(), py::arg("mu") = 0.0,
      py::kw_only(), py::arg("initial_contact_W") = py::none(), py::arg("approach_W") = py::none(),
      py::arg("pose_base") = py::none(), py::arg("pose_angles") = py::none(), py::arg("options") = py::none(),
      py::arg("shapes") = false, py::arg("threads") = py::none(), py::arg("progress") = py::none());

  m.def("max_threads", [] { return omp_get_max_threads(); },
        "Threads a batch uses by default (OpenMP's limit; set OMP_NUM_THREADS to change it).");
}

}  // namespace vibrissa::python
