// Prints the data folder an installed Fastron finds by itself, and that an error thrown inside the
// shared library is caught here by its type.
#include <fastron/core/error.h>
#include <fastron/core/joint_limits.h>
#include <fastron/geometry/robot_library.h>

#include <iostream>
#include <limits>

int main() {
  std::cout << fastron::dataDirectory().string() << '\n';
  try {
    const double q[2] = {0, std::numeric_limits<double>::quiet_NaN()};
    fastron::checkConfiguration(q, 2);
  } catch (const fastron::InvalidArgument& error) {
    std::cout << "caught: " << error.what() << '\n';
    return 0;
  }
  return 1;
}
