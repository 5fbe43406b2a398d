#pragma once
// How Python holds a ProxyCollisionDetector: the bindings of the proxy and of the pipeline make
// them.

#include <pybind11/pybind11.h>

#include <memory>

#include "fastron/proxy/proxy_collision_detector.h"

namespace fastron::python {

/// Stops the background thread without the GIL (its oracle may need it), then deletes.
struct ReleasingDelete {
  void operator()(ProxyCollisionDetector* detector) const {
    pybind11::gil_scoped_release released;
    delete detector;
  }
};
using DetectorHolder = std::unique_ptr<ProxyCollisionDetector, ReleasingDelete>;

}  // namespace fastron::python
