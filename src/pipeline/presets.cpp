#include "fastron/pipeline/presets.h"

namespace fastron::pipeline {

ProxyParams robotProxyParams(double gamma, double beta, std::uint64_t seed) {
  ProxyParams p;
  p.train.kernel = {KernelType::RationalQuadratic, gamma};
  p.train.beta = beta;
  p.train.maxIterations = 20000;
  p.train.maxSupportPoints = kRobotSupportCap;
  p.activeLearning.maxSamples = 500;
  p.seed = seed;
  return p;
}

ProxyParams robotProxyParams(FeatureKind kind, double jointGamma, double jointBeta,
                             std::uint64_t seed, bool selfCollisionLabels) {
  if (kind == FeatureKind::JointScaling) return robotProxyParams(jointGamma, jointBeta, seed);
  const ProxyParams defaults = defaultProxyParams(kind, selfCollisionLabels);
  ProxyParams p = robotProxyParams(defaults.train.kernel.gamma, defaults.train.beta, seed);
  p.train.kernel = defaults.train.kernel;  // with its point terms
  p.activeLearning = defaults.activeLearning;
  p.coldStart = defaults.coldStart;
  return p;
}

ProxyParams forStaticScene(ProxyParams params) {
  params = withWarmStart(params);
  params.activeLearning.maxSamples = 500;
  params.relabelSupport = false;
  return params;
}

ProxyParams withoutBand(ProxyParams params) {
  params.calibrationSamples = 0;
  return params;
}

}  // namespace fastron::pipeline
