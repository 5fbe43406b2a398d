#pragma once
// Cheap, conservative geometry for proving configurations free without an exact check: balls that
// cover each robot shape, volumes that enclose each obstacle (a lower bound on any distance), and
// per-joint levers (an upper bound on how far any point of a shape moves per unit of joint
// motion). Together they give the certificate of Schwarzer, Saha and Latombe's adaptive collision
// checking: a pair of shapes `d` apart at one configuration cannot touch within joint motions
// that move them less than `d` (certified_motion.h).

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/geometry/robot.h"
#include "fastron/geometry/shapes.h"

namespace FASTRON_API fastron {

/// A solid ball.
struct Ball {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
};

/// At most `maxBalls` (>= 1) balls, in the shape's frame, whose union contains every point of
/// `shape` (a mesh: every point of its triangles). Long shapes are cut along their length and
/// meshes (their long triangles cut first) split by their triangles' centroids, so that each ball
/// hugs its part.
std::vector<Ball> coveringBalls(const Shape& shape, std::size_t maxBalls = 12);

/// Balls covering a shape at two levels: `balls` as coveringBalls gives them, and children[i]
/// covering the part of the shape that balls[i] was made for, finer (meshes only; empty for other
/// shapes). A bound that finds two balls overlapping looks at their children.
struct BallCover {
  Ball whole;  ///< encloses every ball
  std::vector<Ball> balls;
  std::vector<std::vector<Ball>> children;  ///< empty, or one list per ball
  /// Balls inside the shape, the cover's dual: one that reaches into an obstacle proves the pair
  /// touching (EnclosingVolume::reachedBy). A mesh's are points of its triangles (radius 0), one
  /// near the middle of each of its finest balls; a solid primitive's are balls inside it (a box's
  /// corners among them).
  std::vector<Ball> inside;
};

/// coveringBalls, and for a mesh up to `maxChildren` children per ball (none when it is below 2),
/// and the balls inside the shape.
BallCover coveringBallTree(const Shape& shape, std::size_t maxBalls = 12,
                           std::size_t maxChildren = 8);

/// Balls' centres and radii as columns (structure of arrays), so that a bound over many balls
/// runs in the machine's vector lanes.
struct BallColumns {
  std::vector<double> x, y, z, radius;
  std::size_t size() const { return radius.size(); }
  /// `balls`, their centres placed by `pose` (the radii kept).
  void place(const Eigen::Isometry3d& pose, const std::vector<Ball>& balls);
  void clear();
  void push(const Eigen::Vector3d& centre, double radius);
};

/// The smallest of |centre - point| - radius over the balls of `columns`: a lower bound on the
/// distance from `point` to any ball (negative where one contains it).
double smallestGap(const BallColumns& columns, const Eigen::Vector3d& point, double pointRadius);

/// A primitive that contains an obstacle, placed in the world, and the distance from a point to
/// it: the obstacle itself for a box, sphere, cylinder or capsule, the box around its vertices for
/// a mesh, around its balls for a point cloud (nothing, infinitely far, for an empty cloud).
class EnclosingVolume {
 public:
  EnclosingVolume(const Shape& shape, const Eigen::Isometry3d& pose);
  /// A lower bound on the distance from `point` (world) to the obstacle; 0 inside it.
  double distanceFrom(const Eigen::Vector3d& point) const;
  /// The smallest of distanceFrom(centre) - radius over the balls of `columns` (world): a lower
  /// bound on the distance from the obstacle to their union. The figures of distanceFrom ball by
  /// ball (to rounding), one loop per kind of volume that runs in the machine's vector lanes
  /// (most of a motion proof's time on robots of primitives went to these bounds).
  double smallestGap(const BallColumns& columns) const;
  /// True when one ball of `columns` (world) reaches more than `depth` into the obstacle: the
  /// obstacle and any shape that contains the ball touch. Always false for a volume that only
  /// encloses its obstacle (a mesh's box, a cloud's).
  bool reachedBy(const BallColumns& columns, double depth) const;

 private:
  /// use(distance), `distance(x, y, z)` being the volume's distance from a point in its own frame:
  /// the one formula per kind that distanceFrom and smallestGap share.
  template <class Use>
  double withLocalDistance(const Use& use) const;
  /// The smallest of figure(x, y, z) - radius over the balls of `columns`, (x, y, z) a ball's
  /// centre in the volume's frame, in blocks that run in vector lanes; it stops after a block
  /// whose smallest is below `enough`.
  template <class Figure>
  double smallestInFrame(const BallColumns& columns, const Figure& figure, double enough) const;

  enum class Kind { Box, Sphere, Cylinder, Capsule, Nothing };
  Kind kind_ = Kind::Box;
  Eigen::Isometry3d toLocal_ = Eigen::Isometry3d::Identity();  ///< world to the volume's frame
  Eigen::Vector3d halfExtents_ = Eigen::Vector3d::Zero();      ///< a box's
  double radius_ = 0, halfLength_ = 0;  ///< a sphere's, cylinder's or capsule's
  bool encloses_ = false;               ///< the volume is larger than the obstacle
};

/// Levers of robot shape `shape` (covered by `balls`, in the shape's frame): for each
/// configuration coordinate k, an upper bound on how far any point of the shape moves, relative to
/// link `relativeTo` (an ancestor of the shape's link, or the root link), per unit of coordinate k,
/// over every configuration. Revolute and continuous joints contribute the largest distance of the
/// shape from their axis (bounded through the chain's lengths and prismatic ranges), prismatic
/// joints 1, mimic joints their multiplier's size times that, joints that do not follow the
/// configuration nothing. A straight joint motion by delta moves every point of the shape by at
/// most sum_k levers[k] * |delta[k]|. Throws InvalidArgument when `relativeTo` is not an ancestor.
Eigen::VectorXd shapeLevers(const Robot& robot, std::size_t shape, const std::vector<Ball>& balls,
                            int relativeTo);

/// A joint that moves a robot shape relative to an ancestor link (shapeMovers): a part of the
/// shape's speed at one configuration.
struct ShapeMover {
  int joint = -1;              ///< in robot.joints(); its axis passes through its child's origin
  std::size_t coordinate = 0;  ///< the configuration coordinate that drives it
  double multiplier = 1;       ///< |d joint value / d coordinate| (a mimic's multiplier)
  bool prismatic = false;
  /// Per configuration coordinate, how fast the joints between this one and the shape can move
  /// the shape's points (their levers, as shapeLevers counts them): how fast a point's distance
  /// from this joint's axis can change along a motion.
  Eigen::VectorXd growth;
};

/// The joints that move robot shape `shape` relative to link `relativeTo` (an ancestor of its
/// link, or the root link), from the shape's link upwards, with the growth of each from `balls`
/// (the shape's, in its frame). At a configuration, a motion by delta moves a point x of the
/// shape by at most the sum over movers m of |delta[m.coordinate]| * m.multiplier * (1 for a
/// prismatic joint, else x's distance from m's axis), and along the motion that distance changes
/// by at most m.growth . |delta|: the levers of shapeLevers, at a configuration. The movers
/// relative to an ancestor are the first ones of those relative to the root. Throws as
/// shapeLevers.
std::vector<ShapeMover> shapeMovers(const Robot& robot, std::size_t shape,
                                    const std::vector<Ball>& balls, int relativeTo);

/// An upper bound, over every configuration, on the distance of any point of any robot shape
/// grown by `padding` from the root link's origin: nothing farther from the robot's base can touch
/// it (clouds are cropped so).
double reachBound(const Robot& robot, double padding = 0);

/// The nearest link that is an ancestor of (or equal to) both links.
int commonAncestor(const Robot& robot, int linkA, int linkB);

}  // namespace fastron
