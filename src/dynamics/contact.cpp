// Objects, contact law and events of contact during motion (include/vibrissa/dynamics/contact.hpp).
#include "vibrissa/dynamics/contact.hpp"

#include <stdexcept>
#include <string>
#include <utility>

#include "vibrissa/core/checks.hpp"

namespace vibrissa::dynamics {

void validate(const LineObstacle& o) {
  require_finite(o.point_W, "object.point");
  require_normalizable(o.direction_W, "object.direction");
  require_finite(o.radius, "object.radius");
  if (o.radius < 0.0) throw std::invalid_argument("object.radius must be >= 0 [m], got " + format_value(o.radius));
  require_finite(o.friction_coefficient, "object.friction_coefficient");
  if (o.friction_coefficient < 0.0)
    throw std::invalid_argument("object.friction_coefficient must be >= 0, got " +
                                format_value(o.friction_coefficient));
}

LineObstacle line_obstacle(const Edge& edge, double mu) {
  validate(edge);
  LineObstacle o;
  o.point_W = edge.point;
  o.direction_W = unit_direction(edge.direction, "edge.direction");
  o.friction_coefficient = mu;
  validate(o);
  return o;
}

LineObstacle line_obstacle(const ObjectContact& object, double mu) {
  validate(object);
  const std::optional<LineCore> core = object.shape->line_core();
  if (!core)
    throw std::invalid_argument("objects in motion must be pegs (an infinite cylinder, or an edge); got a " +
                                std::string(object.shape->type()));
  LineObstacle o;
  o.point_W = object.X_WO.to_world(core->point);
  o.direction_W = (object.X_WO.R_WO * core->direction).normalized();
  o.radius = core->radius;
  o.thickness = object.thickness;
  o.friction_coefficient = mu;
  validate(o);
  return o;
}

void validate(const SurfaceObstacle& o) {
  validate(ObjectContact{o.shape.get(), o.X_WO, o.thickness});
  require_finite(o.friction_coefficient, "object.friction_coefficient");
  if (o.friction_coefficient < 0.0)
    throw std::invalid_argument("object.friction_coefficient must be >= 0, got " +
                                format_value(o.friction_coefficient));
}

void validate(const Obstacle& o) {
  std::visit([](const auto& x) { validate(x); }, o);
}

double friction_coefficient(const Obstacle& o) {
  return std::visit([](const auto& x) { return x.friction_coefficient; }, o);
}

Obstacle obstacle(std::shared_ptr<const Shape> shape, const ObjectPose& X_WO, bool thickness, double mu) {
  const ObjectContact contact{shape.get(), X_WO, thickness};
  validate(contact);
  if (shape->line_core()) return line_obstacle(contact, mu);
  SurfaceObstacle o{std::move(shape), X_WO, thickness, mu};
  validate(o);
  return o;
}

void validate(const ContactLaw& law) {
  require_positive(law.stiffness, "contact.stiffness");
  require_finite(law.tangential_stiffness, "contact.tangential_stiffness");
  if (law.tangential_stiffness < 0.0)
    throw std::invalid_argument("contact.tangential_stiffness must be >= 0 [N/m], got " +
                                format_value(law.tangential_stiffness));
  require_finite(law.damping_ratio, "contact.damping_ratio");
  if (law.damping_ratio < 0.0)
    throw std::invalid_argument("contact.damping_ratio must be >= 0, got " + format_value(law.damping_ratio));
}

std::string_view to_string(ContactState s) {
  switch (s) {
    case ContactState::none: return "none";
    case ContactState::stick: return "stick";
    case ContactState::slip: return "slip";
  }
  return "unknown";
}

std::string_view to_string(ContactEventType t) {
  switch (t) {
    case ContactEventType::touch: return "touch";
    case ContactEventType::slip: return "slip";
    case ContactEventType::stick: return "stick";
    case ContactEventType::release: return "release";
  }
  return "unknown";
}

}  // namespace vibrissa::dynamics
