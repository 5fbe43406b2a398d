#pragma once
// The training settings of robot models that the commands, Python and the experiments share.

#include <cstdint>

#include "fastron/core/export.h"
#include "fastron/core/feature_map.h"
#include "fastron/proxy/proxy_collision_detector.h"

namespace FASTRON_API fastron {
namespace pipeline {

/// A robot model's settings: the rational-quadratic kernel of width `gamma`, conditional bias
/// `beta`, 20000 iterations per update, at most kRobotSupportCap support points, 500
/// active-learning points per update (paper, Sec. IV-B).
ProxyParams robotProxyParams(double gamma, double beta, std::uint64_t seed);
/// The same with the kernel, beta, active-learning points and cold start of `kind`
/// (defaultProxyParams, given whether the labels include self-collisions) for task-space
/// features, and `jointGamma`, `jointBeta` (e.g. the paper's) for joints.
ProxyParams robotProxyParams(FeatureKind kind, double jointGamma, double jointBeta,
                             std::uint64_t seed, bool selfCollisionLabels = false);
/// `params` for a scene that stands still (`fastron plan`, motion-bench, shelf): the paper's update
/// (withWarmStart) with 500 active-learning points for every kind of features. Updates from zero
/// weights (defaultProxyParams) undo weights that a changing world made stale; where nothing goes
/// stale they only grew the mesh Panda's models (motion-bench: |S| 1906 -> 3410, median 5.4x ->
/// 4.6x FCL's; docs/algorithms.md).
ProxyParams forStaticScene(ProxyParams params);
/// `params` with no calibration points (ProxyParams::calibrationSamples = 0): for a model that
/// plans without an uncertainty band, or the paper's pipeline, which has none.
ProxyParams withoutBand(ProxyParams params);

}  // namespace pipeline
}  // namespace fastron
