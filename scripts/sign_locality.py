#!/usr/bin/python3
"""How much of a model's kernel sum its sign needs: the test of whether a query could stop early.

For uniform configurations q, the terms t_i = w_i k(s_i, q) of f(q) = sum_i t_i are computed and
reported as:
- cancellation: sum_i |t_i| / |f(q)| (median): how many times larger the terms are than their sum;
- oracle share: the fewest terms, taken largest |t_i| first, after which the rest (bounded by
  their own sum of |t_i|) can no longer change the sign. No early exit that bounds terms from
  outside (a spatial index, any order) can read fewer terms than this;
- cluster oracle share: the same with the support set split into clusters of LEAF points
  (median splits along the widest feature, as a spatial index would) and each cluster's exact net
  sum in place of its terms: what an index whose far-field bounds were perfect would read.

Usage (with the Python module built, e.g. PYTHONPATH=build/release/python):
  /usr/bin/python3 scripts/sign_locality.py ROBOT MODEL [--queries N] [--leaf LEAF] [--srdf F]
"""
import argparse

import numpy as np

import fastron


def kernel_of(r2, kind, gamma):
    if kind == "rq":
        return 1.0 / (1.0 + 0.5 * gamma * r2) ** 2
    return np.exp(-gamma * r2)


def terms(model, x):
    """w_i k(s_i, x) for every support point, as Kernel::between computes it (double)."""
    s = np.asarray(model.support_features)
    w = np.asarray(model.weights)
    kind, gamma, block = model.kernel, model.gamma, model.kernel_block
    diff2 = (s - x) ** 2
    if block == 0:
        return w * kernel_of(diff2.sum(axis=1), kind, gamma)
    blocks = diff2.reshape(len(s), -1, block).sum(axis=2)
    share = model.kernel_whole_share
    point_weight = (1.0 - share) / blocks.shape[1]
    k = share * kernel_of(blocks.sum(axis=1), kind, gamma)
    k += point_weight * kernel_of(blocks, kind, gamma).sum(axis=1)
    return w * k


def oracle_share(values):
    """Fewest values (largest |value| first) after which the rest cannot change the sign."""
    largest_first = values[np.argsort(-np.abs(values), kind="stable")]
    partial = np.cumsum(largest_first)
    tail = np.abs(values).sum() - np.cumsum(np.abs(largest_first))
    decided = np.nonzero(np.abs(partial) > tail)[0]
    used = decided[0] + 1 if len(decided) else len(values)
    return used / len(values)


def clusters(points, leaf):
    """Index lists of median splits along the widest feature, down to `leaf` points."""
    out, stack = [], [np.arange(len(points))]
    while stack:
        idx = stack.pop()
        if len(idx) <= leaf:
            out.append(idx)
            continue
        spread = points[idx].max(axis=0) - points[idx].min(axis=0)
        order = idx[np.argsort(points[idx, int(np.argmax(spread))], kind="stable")]
        stack += [order[: len(order) // 2], order[len(order) // 2 :]]
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robot")
    parser.add_argument("model")
    parser.add_argument("--srdf", default="")
    parser.add_argument("--queries", type=int, default=500)
    parser.add_argument("--leaf", type=int, default=16)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    robot = fastron.load_robot(args.robot, srdf=args.srdf or None)
    model = fastron.load_model(args.model, robot)
    limits = model.limits
    rng = np.random.default_rng(args.seed)
    q = rng.uniform(limits.lower, limits.upper, size=(args.queries, model.dim))
    x = model.features.map(q)
    groups = clusters(np.asarray(model.support_features), args.leaf)
    cancel, share, cluster_share = [], [], []
    for row in x:
        t = terms(model, row)
        cancel.append(np.abs(t).sum() / max(abs(t.sum()), 1e-300))
        share.append(oracle_share(t))
        cluster_share.append(oracle_share(np.array([t[g].sum() for g in groups])))
    w = np.asarray(model.weights)
    print(f"model        {args.model}: |S| {model.support_count}, kernel {model.kernel} gamma "
          f"{model.gamma:g}, block {model.kernel_block}, sum|w| {np.abs(w).sum():.0f}")
    print(f"queries      {args.queries} uniform configurations (seed {args.seed})")
    print(f"cancellation sum|t|/|f| median {np.median(cancel):.0f}")
    print(f"oracle share of terms: median {np.median(share):.3f}, p90 "
          f"{np.quantile(share, 0.9):.3f}")
    print(f"cluster oracle share ({len(groups)} clusters of <= {args.leaf}): median "
          f"{np.median(cluster_share):.3f}, p90 {np.quantile(cluster_share, 0.9):.3f}")


if __name__ == "__main__":
    main()
