#pragma once
// Smaller models from a trained one: dropping support points that no held-out answer needs, or
// merging nearby ones (the D-Fastron idea). Measured in docs/algorithms.md ("Smaller support
// sets"): on the task-space models of `fastron bench changing` neither makes a model smaller at
// equal accuracy, so the pipeline publishes Algorithm 1's support set as it is.

#include <memory>

#include "fastron/core/export.h"
#include "fastron/core/model.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

/// A model with the support points of `model` that the answers on `heldOut` need: support points
/// are tried in order of increasing |weight|, and one is dropped when, without it, every row of
/// `heldOut` keeps its answer (f > 0, collision, or f <= 0, free; f summed in double as in
/// training). The weights of the points kept do not change. `heldOut` needs no labels; it should
/// be configurations the model was not trained on, spread as its queries will be (e.g. uniform):
/// answers elsewhere are not checked. For queries only: Algorithm 1's guarantees (Claim 1) hold
/// for the trained model, not for the pruned one. Throws InvalidArgument when `heldOut` does not
/// have model.dim() columns or has a non-finite value.
std::shared_ptr<const Model> pruneSupport(const Model& model, const Configurations& heldOut);

/// A model whose support points of one sign closer than `radius` to each other in feature space
/// are merged into one (D-Fastron's clustering of the support set in task space): the points are
/// taken in order of decreasing |weight|, each joins the first kept point of its sign within
/// `radius` and adds its weight to it, or is kept. The kept points stay where they are (a
/// position in task space may have no configuration). Throws InvalidArgument unless radius is
/// finite and >= 0.
std::shared_ptr<const Model> mergeSupport(const Model& model, double radius);

}  // namespace fastron
