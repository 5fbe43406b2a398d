#include "fastron/geometry/scene_checker.h"

#include "fastron/core/error.h"
#include "fastron/core/joint_limits.h"

namespace fastron {

std::string describe(const Contact& contact) {
  return contact.robotLink + (contact.selfCollision ? " touches link " : " touches ") +
         contact.other;
}

std::optional<Contact> SceneChecker::firstContact(std::span<const double> q) const {
  checkConfiguration(q, dof());
  return contactAt(q.data());
}

double SceneChecker::distance(std::span<const double> q) const {
  checkConfiguration(q, dof());
  return distanceAt(q.data());
}

double SceneChecker::distanceAt(const double* /*q*/) const {
  throw Unsupported(name() + " does not measure distances");
}

}  // namespace fastron
