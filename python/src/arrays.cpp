#include "arrays.h"

#include <cmath>
#include <string>

#include "fastron/core/error.h"

namespace fastron::python {

namespace {

std::string shapeText(const py::array& a) {
  std::string text;
  for (py::ssize_t i = 0; i < a.ndim(); ++i)
    text += (i > 0 ? ", " : "") + std::to_string(a.shape(i));
  return "(" + text + (a.ndim() == 1 ? ",)" : ")");
}

/// `value` as a float64 C-ordered array; a dtype that is not a real number or a boolean (strings,
/// objects, complex numbers) is refused rather than converted.
py::array_t<double, py::array::c_style> asDoubles(py::handle value, const char* name) {
  const py::array any = py::array::ensure(value);
  if (!any) {
    throw InvalidArgument(std::string(name) + ": expected an array of numbers, got " +
                          typeName(value));
  }
  const char kind = any.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
    throw InvalidArgument(std::string(name) + ": expected real numbers, got an array of dtype " +
                          std::string(py::str(any.dtype())));
  }
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(any);
}

}  // namespace

ConfigurationRows configurations(py::handle value, std::size_t dim, const char* name,
                                 bool allowSingle) {
  ConfigurationRows rows;
  rows.array = asDoubles(value, name);
  const py::array_t<double, py::array::c_style>& a = rows.array;
  const std::string expected = dim == 0 ? std::string("d") : std::to_string(dim);
  const std::string wanted =
      allowSingle ? " (" + expected + ",) or (n, " + expected + ")" : " (n, " + expected + ")";
  if (a.ndim() == 1 && allowSingle) {
    rows.single = true;
    rows.rows = 1;
    rows.cols = static_cast<std::size_t>(a.shape(0));
  } else if (a.ndim() == 2) {
    rows.rows = static_cast<std::size_t>(a.shape(0));
    rows.cols = static_cast<std::size_t>(a.shape(1));
  } else {
    throw InvalidArgument(std::string(name) + ": expected shape" + wanted + ", got shape " +
                          shapeText(a));
  }
  if ((dim != 0 && rows.cols != dim) || rows.cols == 0) {
    throw InvalidArgument(std::string(name) + ": expected shape" + wanted + ", got shape " +
                          shapeText(a));
  }
  rows.data = a.data();
  for (std::size_t i = 0; i < rows.rows * rows.cols; ++i) {
    if (!std::isfinite(rows.data[i])) {
      const std::string at =
          rows.single ? std::to_string(i)
                      : std::to_string(i / rows.cols) + ", " + std::to_string(i % rows.cols);
      throw InvalidArgument(std::string(name) + "[" + at + "] is " + std::to_string(rows.data[i]) +
                            ": configurations must be finite");
    }
  }
  return rows;
}

Eigen::VectorXd vector(py::handle value, std::size_t dim, const char* name) {
  const ConfigurationRows rows = configurations(value, dim, name);
  if (!rows.single) {
    throw InvalidArgument(std::string(name) + ": expected one configuration of shape (" +
                          std::to_string(dim) + ",), got shape (" + std::to_string(rows.rows) +
                          ", " + std::to_string(rows.cols) + ")");
  }
  return Eigen::Map<const Eigen::VectorXd>(rows.data, static_cast<Eigen::Index>(rows.cols));
}

Labels labels(py::handle value, std::size_t rows, const char* name) {
  const py::array_t<double, py::array::c_style> a = asDoubles(value, name);
  if (a.ndim() != 1 || static_cast<std::size_t>(a.shape(0)) != rows) {
    throw InvalidArgument(std::string(name) + ": expected shape (" + std::to_string(rows) +
                          ",) (one label per configuration), got shape " + shapeText(a));
  }
  const bool booleans = py::array::ensure(value).dtype().kind() == 'b';
  Labels out(rows);
  for (std::size_t i = 0; i < rows; ++i) {
    const double v = a.data()[i];
    if (booleans) {
      out[i] = v != 0 ? 1 : -1;
    } else if (v == 1 || v == -1) {
      out[i] = static_cast<std::int8_t>(v);
    } else {
      throw InvalidArgument(std::string(name) + "[" + std::to_string(i) + "] is " +
                            std::to_string(v) +
                            ": labels are +1 (in collision) and -1 (free), or booleans");
    }
  }
  return out;
}

py::array_t<double> newArray(std::size_t rows, std::size_t cols) {
  if (cols == 0) return py::array_t<double>(static_cast<py::ssize_t>(rows));
  return py::array_t<double>({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
}

py::array_t<double> pathArray(const std::vector<Eigen::VectorXd>& path, std::size_t dim) {
  py::array_t<double> out = newArray(path.size(), dim);
  for (std::size_t i = 0; i < path.size(); ++i)
    std::copy(path[i].data(), path[i].data() + dim, out.mutable_data() + i * dim);
  return out;
}

std::vector<Eigen::VectorXd> pathOf(py::handle waypoints, std::size_t dim, const char* name) {
  const ConfigurationRows rows = configurations(waypoints, dim, name, false);
  std::vector<Eigen::VectorXd> path;
  for (std::size_t i = 0; i < rows.rows; ++i)
    path.emplace_back(Eigen::Map<const Eigen::VectorXd>(rows.data + i * rows.cols,
                                                        static_cast<Eigen::Index>(rows.cols)));
  return path;
}

py::array_t<double> toArray(const std::vector<double>& v) {
  return toArray(Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
}

py::array_t<std::int8_t> toArray(const Labels& labels) {
  py::array_t<std::int8_t> out(static_cast<py::ssize_t>(labels.size()));
  std::copy(labels.begin(), labels.end(), out.mutable_data());
  return out;
}

std::string typeName(py::handle value) {
  return py::str(py::type::handle_of(value).attr("__name__"));
}

}  // namespace fastron::python
