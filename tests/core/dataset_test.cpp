#include "fastron/core/dataset.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fastron/core/csv_table.h"
#include "fastron/core/error.h"
#include "temp_dir.h"

namespace fastron {
namespace {

using test::messageOf;
using ::testing::HasSubstr;

class DatasetFiles : public test::TempDir {
 protected:
  std::string csvError(const std::string& content) {
    write("d.csv", content);
    return messageOf<FileError>([&] { readCsv(path("d.csv")); });
  }
};

TEST_F(DatasetFiles, ReadsCsvWithHeader) {
  write("d.csv", "q1, q2 ,label\n0.5,-1.25,+1\n\n3e-1,2,-1\r\n");
  const Dataset data = readDataset(path("d.csv"));
  ASSERT_EQ(data.size(), 2u);
  ASSERT_EQ(data.dim(), 2u);
  EXPECT_EQ(data.points(0, 0), 0.5);
  EXPECT_EQ(data.points(0, 1), -1.25);
  EXPECT_EQ(data.points(1, 0), 0.3);
  EXPECT_EQ(data.labels, (Labels{1, -1}));
  EXPECT_EQ(data.columnNames, (std::vector<std::string>{"q1", "q2"}));
}

// The table under datasets and path files: the header, and each row's own line in the file.
TEST(CsvTable, KeepsTheHeaderAndEachRowsLine) {
  const CsvTable table = parseCsvTable("\n x , y\n1,2\n\n 3 ,+4\r\n", "t.csv");
  EXPECT_EQ(table.header, (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(table.columns, 2u);
  EXPECT_EQ(table.firstLine, 2u);
  EXPECT_EQ(table.lineNumbers, (std::vector<std::size_t>{3, 5}));
  EXPECT_EQ(table.values, (std::vector<double>{1, 2, 3, 4}));
  EXPECT_EQ(table.at(1, 0), 3);
  const CsvTable empty = parseCsvTable("\n\n", "e.csv");
  EXPECT_EQ(empty.rows(), 0u);
  EXPECT_EQ(empty.firstLine, 0u);
  EXPECT_THAT(messageOf<FileError>([] { parseCsvTable("1,2\n\n3\n", "t.csv"); }),
              HasSubstr("t.csv:3: 1 columns, expected 2"));
}

TEST_F(DatasetFiles, ReadsCsvWithoutHeader) {
  write("d.csv", "1,2,3,1.0\n4,5,6,-1\n");
  const Dataset data = readCsv(path("d.csv"));
  EXPECT_EQ(data.dim(), 3u);
  EXPECT_TRUE(data.columnNames.empty());
  EXPECT_EQ(data.labels, (Labels{1, -1}));
}

TEST_F(DatasetFiles, CsvRoundTrip) {
  Dataset data;
  data.points = Configurations::Random(50, 4);
  data.labels.assign(50, -1);
  data.labels[7] = 1;
  data.columnNames = {"a", "b", "c", "d"};
  writeCsv(data, path("r.csv"));
  const Dataset back = readCsv(path("r.csv"));
  EXPECT_EQ(back.points, data.points);
  EXPECT_EQ(back.labels, data.labels);
  EXPECT_EQ(back.columnNames, data.columnNames);
}

TEST_F(DatasetFiles, WriteDatasetChoosesTheFormatByExtension) {
  Dataset data;
  data.points = Configurations::Random(20, 3);
  data.labels.assign(20, 1);
  for (const char* name : {"w.csv", "w.npy"}) {
    writeDataset(data, path(name));
    const Dataset back = readDataset(path(name));
    EXPECT_EQ(back.points, data.points) << name;
    EXPECT_EQ(back.labels, data.labels) << name;
  }
  EXPECT_EQ(read(path("w.npy")).substr(1, 5), "NUMPY");
  EXPECT_THAT(messageOf<FileError>([&] { writeDataset(data, path("w.dat")); }),
              HasSubstr("w.dat: unknown dataset format '.dat'"));
}

TEST_F(DatasetFiles, BadCsvRowsNameTheLineAndColumn) {
  EXPECT_THAT(csvError("q1,q2,label\n0,0,1\n0,1\n"), HasSubstr("d.csv:3: 2 columns, expected 3"));
  EXPECT_THAT(csvError("0,0,1\n0,abc,1\n"), HasSubstr("d.csv:2: column 2: 'abc' is not a number"));
  EXPECT_THAT(csvError("0,nan,1\n"), HasSubstr("d.csv:1: column 2: value is not finite"));
  EXPECT_THAT(csvError("0,0,1\n-inf,0,1\n"), HasSubstr("d.csv:2: column 1: value is not finite"));
  EXPECT_THAT(csvError("0,0,0.5\n"), HasSubstr("d.csv:1: column 3: label must be +1 or -1"));
  EXPECT_THAT(csvError("0,0,1,\n"), HasSubstr("column 4: '' is not a number"));
  EXPECT_THAT(csvError("label\n1\n"), HasSubstr("at least one configuration column"));
  EXPECT_THAT(csvError(""), HasSubstr("no data rows"));
  EXPECT_THAT(csvError("q1,label\n"), HasSubstr("no data rows"));
  EXPECT_THAT(messageOf<FileError>([&] { readDataset(path("absent.csv")); }),
              HasSubstr("absent.csv: cannot open"));
  write("d.json", "{}");
  EXPECT_THAT(messageOf<FileError>([&] { readDataset(path("d.json")); }),
              HasSubstr("unknown dataset format"));
}

TEST_F(DatasetFiles, NpyRoundTrip) {
  Dataset data;
  data.points = Configurations::Random(33, 5);
  data.labels.assign(33, 1);
  data.labels[0] = -1;
  writeNpy(data, path("d.npy"));
  const std::string bytes = read(path("d.npy"));
  EXPECT_EQ((bytes.size() - 33 * 6 * 8) % 64, 0u);  // header aligned as NumPy does
  const Dataset back = readDataset(path("d.npy"));
  EXPECT_EQ(back.points, data.points);
  EXPECT_EQ(back.labels, data.labels);
}

std::string npyBytes(const std::string& dict, const std::string& payload) {
  std::string header = dict;
  header.append(63 - (10 + header.size()) % 64, ' ');
  header.push_back('\n');
  std::string bytes = "\x93NUMPY\x01";
  bytes.push_back('\0');
  bytes.push_back(static_cast<char>(header.size()));
  bytes.push_back('\0');
  return bytes + header + payload;
}

TEST_F(DatasetFiles, ReadsFloat32AndFortranOrder) {
  // Column-major (2, 2) float32: rows (0.5, 1) and (0.25, -1).
  std::string payload;
  for (const float v : {0.5f, 0.25f, 1.0f, -1.0f})
    payload.append(reinterpret_cast<const char*>(&v), 4);
  write("f.npy", npyBytes("{'descr': '<f4', 'fortran_order': True, 'shape': (2, 2), }", payload));
  const Dataset data = readNpy(path("f.npy"));
  EXPECT_EQ(data.points(0, 0), 0.5);
  EXPECT_EQ(data.points(1, 0), 0.25);
  EXPECT_EQ(data.labels, (Labels{1, -1}));
}

TEST_F(DatasetFiles, BadNpyFilesAreRefused) {
  auto error = [&](const std::string& bytes) {
    write("b.npy", bytes);
    return messageOf<FileError>([&] { readNpy(path("b.npy")); });
  };
  const std::string twoRows(2 * 2 * 8, '\0');
  EXPECT_THAT(error("PK\x03\x04 not numpy"), HasSubstr("bad magic"));
  EXPECT_THAT(error(npyBytes("{'descr': '<f8', 'fortran_order': False, 'shape': (4,), }", twoRows)),
              HasSubstr("2-D array"));
  EXPECT_THAT(
      error(npyBytes("{'descr': '<c16', 'fortran_order': False, 'shape': (2, 2), }", twoRows)),
      HasSubstr("unsupported .npy dtype '<c16'"));
  EXPECT_THAT(
      error(npyBytes("{'descr': '<f8', 'fortran_order': False, 'shape': (9, 2), }", twoRows)),
      HasSubstr("truncated .npy data"));
  EXPECT_THAT(error(npyBytes("{'fortran_order': False, 'shape': (2, 2), }", twoRows)),
              HasSubstr("no 'descr' field"));
  // Zero labels in an otherwise valid file.
  EXPECT_THAT(
      error(npyBytes("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }", twoRows)),
      HasSubstr("row 0, column 1: label must be +1 or -1"));
  std::string truncatedHeader = "\x93NUMPY\x01";
  truncatedHeader += std::string("\0\xff\x00", 3);
  EXPECT_THAT(error(truncatedHeader), HasSubstr("truncated .npy header"));
}

// Found by fuzz/npy_fuzzer: a header field with a newline in it made a two-line message. Every
// fastron::Error is one line, whatever it quotes.
TEST_F(DatasetFiles, MessagesQuotingTheFileStayOnOneLine) {
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (2,\n 3), }";
  std::string bytes = "\x93NUMPY";
  bytes += '\x01';
  bytes += '\x00';
  bytes += static_cast<char>(header.size());
  bytes += '\x00';
  bytes += header;
  const std::string message = messageOf<FileError>([&] { parseNpy(bytes, "n.npy"); });
  EXPECT_THAT(message, HasSubstr("n.npy: bad .npy shape '2,\\n 3'"));
  EXPECT_EQ(message.find('\n'), std::string::npos);
  EXPECT_STREQ(Error("a\nb\tc\x01").what(), "a\\nb\\tc\\x01");
}

TEST_F(DatasetFiles, ParsesFromMemoryAsFromAFile) {
  write("d.csv", "a,b,label\n0.5,1,1\n");
  const Dataset fromFile = readCsv(path("d.csv"));
  const Dataset fromText = parseCsv("a,b,label\n0.5,1,1\n", "d.csv");
  EXPECT_EQ(fromText.points, fromFile.points);
  EXPECT_EQ(fromText.labels, fromFile.labels);
  EXPECT_EQ(fromText.columnNames, fromFile.columnNames);
}

TEST(DatasetAppend, AppendsRowsWithTheirLabels) {
  Dataset first{Configurations::Random(3, 2), {1, -1, 1}, {}};
  const Dataset second{Configurations::Random(2, 2), {-1, -1}, {}};
  Dataset all;
  append(all, first);  // an empty dataset takes the rows' columns
  append(all, second);
  append(all, Dataset{});  // nothing to append
  ASSERT_EQ(all.size(), 5u);
  ASSERT_EQ(all.points.rows(), 5);
  EXPECT_EQ(all.points.topRows(3), first.points);
  EXPECT_EQ(all.points.bottomRows(2), second.points);
  EXPECT_EQ(all.labels, (Labels{1, -1, 1, -1, -1}));
  EXPECT_THAT(messageOf<InvalidArgument>([&] {
                append(first, Dataset{Configurations::Zero(1, 3), {1}, {}});
              }),
              HasSubstr("cannot append rows of 3 columns to a dataset of 2"));
}

TEST(DatasetSplit, HoldsOutAShareAndKeepsFileOrderWithoutOne) {
  Dataset data;
  data.points = Configurations::Random(10, 2);
  for (int i = 0; i < 10; ++i) data.labels.push_back(i % 2 == 0 ? 1 : -1);
  const DatasetSplit none = splitHoldout(data, 0, 1);
  EXPECT_EQ(none.train.points, data.points);
  EXPECT_EQ(none.test.size(), 0u);
  const DatasetSplit split = splitHoldout(data, 0.3, 1);
  ASSERT_EQ(split.test.size(), 3u);
  ASSERT_EQ(split.train.size(), 7u);
  // Every row lands once, with its label.
  std::size_t found = 0;
  for (const Dataset* part : {&split.train, &split.test}) {
    for (Eigen::Index r = 0; r < part->points.rows(); ++r) {
      for (Eigen::Index i = 0; i < 10; ++i) {
        if (part->points.row(r) == data.points.row(i)) {
          ++found;
          EXPECT_EQ(part->labels[static_cast<std::size_t>(r)],
                    data.labels[static_cast<std::size_t>(i)]);
        }
      }
    }
  }
  EXPECT_EQ(found, 10u);
  EXPECT_EQ(splitHoldout(data, 0.3, 1).test.points, split.test.points);  // the seed decides
  EXPECT_THROW(splitHoldout(data, 1, 1), InvalidArgument);
}

}  // namespace
}  // namespace fastron
