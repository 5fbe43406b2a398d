#pragma once
// Labelled datasets: CSV (configuration columns, then the label +1 / -1; optional header row)
// and NumPy .npy (a 2-D array whose last column is the label).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "fastron/core/export.h"
#include "fastron/core/types.h"

namespace FASTRON_API fastron {

struct Dataset {
  Configurations points;                 ///< one configuration per row
  Labels labels;                         ///< +1 in collision, -1 free
  std::vector<std::string> columnNames;  ///< from the CSV header, if any (configuration columns)

  std::size_t size() const { return labels.size(); }
  std::size_t dim() const { return static_cast<std::size_t>(points.cols()); }
};

/// Reads a .csv or .npy file (chosen by extension). Throws FileError naming the file, and for
/// CSV the line and column, of the first problem: unreadable file, no data, ragged row, value
/// that is not a number, NaN or infinite value, label other than +1 / -1.
Dataset readDataset(const std::filesystem::path& path);
Dataset readCsv(const std::filesystem::path& path);
Dataset readNpy(const std::filesystem::path& path);
/// The same readers on the bytes of a file; errors name `source` as they would the file.
Dataset parseCsv(std::string_view text, const std::string& source);
Dataset parseNpy(std::string_view bytes, const std::string& source);

/// The rows of `data` at `index`, in that order (column names kept).
Dataset rowsOf(const Dataset& data, const std::vector<Eigen::Index>& index);

/// Appends the rows of `rows` to `data` (an empty `data` takes `rows`' columns). Throws
/// InvalidArgument when both have rows and their column counts differ.
void append(Dataset& data, const Dataset& rows);

/// A random share `heldOut` (in [0, 1)) of the rows for validation, the rest for training. With
/// nothing held out the training rows keep the data's order (the same model as training on the
/// whole file); otherwise the rows are shuffled with `seed` first. Throws InvalidArgument on a
/// share outside [0, 1).
struct DatasetSplit {
  Dataset train, test;
};
DatasetSplit splitHoldout(const Dataset& data, double heldOut, std::uint64_t seed);

/// Writes a .csv or .npy file (chosen by extension, as readDataset reads them); throws FileError
/// naming the file for another extension.
void writeDataset(const Dataset& data, const std::filesystem::path& path);
/// Writes configuration columns and the label; with column names, a header row first.
void writeCsv(const Dataset& data, const std::filesystem::path& path);
/// Writes a float64 C-order array of shape (n, d + 1).
void writeNpy(const Dataset& data, const std::filesystem::path& path);

}  // namespace fastron
