#include "rigid/io/table.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/expect_error.hpp"

namespace rigid::io {
namespace {

namespace fs = std::filesystem;

TEST(Table, CsvRoundTripsEveryBit) {
  // Doubles chosen to need all 17 significant digits, subnormals and extremes.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  Table t({"t", "q", "v"});
  t.add_row(std::vector<double>{0.1, 1.0 / 3.0, std::nextafter(1.0, 2.0)});
  t.add_row(std::vector<double>{std::numeric_limits<double>::denorm_min(),
                                std::numeric_limits<double>::max(), -0.0});
  for (int i = 0; i < 1000; ++i) t.add_row(std::vector<double>{u(rng), u(rng) * 1e-200, u(rng) * 1e200});
  const fs::path file = fs::temp_directory_path() / "rigid_table_roundtrip.csv";
  write_csv(file, t);
  const Table back = read_csv(file);
  ASSERT_EQ(back.columns(), t.columns());
  ASSERT_EQ(back.rows(), t.rows());
  for (std::size_t i = 0; i < t.data().size(); ++i) {
    EXPECT_EQ(std::memcmp(&back.data()[i], &t.data()[i], sizeof(double)), 0) << "value " << i;
  }
}

TEST(Table, NpyHeaderFollowsFormat10) {
  Table t({"a", "b", "c"});
  t.add_row(std::vector<double>{1, 2, 3});
  t.add_row(std::vector<double>{4, 5, 6});
  const std::string npy = to_npy(t);
  ASSERT_GE(npy.size(), 10u);
  EXPECT_EQ(npy.substr(0, 6), "\x93NUMPY");
  const std::size_t header_len = static_cast<unsigned char>(npy[8]) + 256u * static_cast<unsigned char>(npy[9]);
  // The data starts 64-byte aligned and is exactly rows*cols doubles.
  EXPECT_EQ((10 + header_len) % 64, 0u);
  EXPECT_EQ(npy.size(), 10 + header_len + 6 * sizeof(double));
  const std::string header = npy.substr(10, header_len);
  EXPECT_NE(header.find("'shape': (2, 3)"), std::string::npos);
  EXPECT_EQ(header.back(), '\n');
  double last = 0;
  std::memcpy(&last, npy.data() + npy.size() - sizeof(double), sizeof(double));
  EXPECT_EQ(last, 6.0);
}

TEST(Table, BadInputIsNamed) {
  EXPECT_RIGID_ERROR(Table({"a", "a"}), "column name 'a' appears twice");
  Table t({"a", "b"});
  EXPECT_RIGID_ERROR(t.add_row(std::vector<double>{1}), "row has 1 values, expected 2");
  EXPECT_RIGID_ERROR((void)t.column("c"), "no column 'c'; the columns are a, b");

  const fs::path file = fs::temp_directory_path() / "rigid_table_bad.csv";
  {
    std::ofstream out(file);
    out << "a,b\n1,2\n3,x4\n";
  }
  EXPECT_RIGID_ERROR((void)read_csv(file), file.string() + ":3:3: 'x4' is not a number");
  {
    std::ofstream out(file);
    out << "a,b\n1,2,3\n";
  }
  EXPECT_RIGID_ERROR((void)read_csv(file), file.string() + ":2:1: row has 3 fields, expected 2");
  // a header's repeated or empty name, at its place in the file
  {
    std::ofstream out(file);
    out << "t,x,t\n1,2,3\n";
  }
  EXPECT_RIGID_ERROR((void)read_csv(file),
                     file.string() + ":1:5: column name 't' appears twice in the header");
  {
    std::ofstream out(file);
    out << "t,,x\n1,2,3\n";
  }
  EXPECT_RIGID_ERROR((void)read_csv(file),
                     file.string() + ":1:3: column 2 of the header has an empty name");
  // a control character in a name, quoted escaped at its own column: "b\r" (the line's last CR
  // is its CRLF ending) would be written back as "b" and read so (a csv_table fuzz finding)
  {
    std::ofstream out(file, std::ios::binary);
    out << "a,b\r\r\n1,2\n";
  }
  EXPECT_RIGID_ERROR((void)read_csv(file), file.string() +
                                               ":1:4: column name 'b\\x0d' holds a control "
                                               "character; expected printable names");
  {
    std::ofstream out(file, std::ios::binary);
    out << "a,b\n1,\x1b[31m\n";
  }
  EXPECT_RIGID_ERROR((void)read_csv(file), file.string() + ":2:3: '\\x1b[31m' is not a number");
  EXPECT_RIGID_ERROR((void)read_csv(file.string() + ".missing"), "cannot open");
}

TEST(Table, CsvTextColumnIsQuotedAsRfc4180Says) {
  Table t({"run", "x"});
  t.add_row(std::vector<double>{0, 0.1});
  t.add_row(std::vector<double>{1, std::nan("")});
  t.add_row(std::vector<double>{2, -2.5});
  const std::vector<std::string> text{"", "file.toml:3:1: a, b \"c\"\nd", "plain"};
  // a field with a comma, quote or line break goes in quotes with each quote doubled
  EXPECT_EQ(to_csv(t, "error", text), "run,x,error\n0,0.1,\n1,nan,\"file.toml:3:1: a, b \"\"c\"\"\nd\"\n2,-2.5,plain\n");
  // a table without rows: the header alone
  EXPECT_EQ(to_csv(Table({"a"}), "e", {}), "a,e\n");
  EXPECT_RIGID_ERROR((void)to_csv(t, "error", std::vector<std::string>{"one"}), "1 texts for a table of 3 rows");
  EXPECT_RIGID_ERROR((void)to_csv(t, "", text), "empty name");
}

// Formatted in blocks on several threads, the text is that of one thread: the rows split at
// rows·b/blocks, for tables just below, at and above one block's 4096 rows a thread, and with
// more threads than blocks; each line reads back to the same bits.
TEST(Table, CsvOnSeveralThreadsIsTheTextOfOne) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (const std::size_t rows : {0u, 1u, 4095u, 8192u, 3u * 4096u + 17u}) {
    Table t({"run", "x"});
    std::vector<std::string> text;
    for (std::size_t r = 0; r < rows; ++r) {
      t.add_row(std::vector<double>{static_cast<double>(r), u(rng) * 1e-100});
      text.push_back(r % 7 == 0 ? "a, \"b\"" : "");
    }
    const std::string one = to_csv(t), one_text = to_csv(t, "error", text);
    for (const std::size_t threads : {0u, 2u, 3u, 4u, 64u}) {
      EXPECT_EQ(to_csv(t, threads), one) << rows << " rows, " << threads << " threads";
      EXPECT_EQ(to_csv(t, "error", text, threads), one_text) << rows << " rows, " << threads << " threads";
    }
    const fs::path file = fs::temp_directory_path() / "rigid_table_threads.csv";
    {
      std::ofstream(file, std::ios::binary) << to_csv(t, 3);
    }
    const Table back = read_csv(file);
    ASSERT_EQ(back.rows(), rows);
    if (rows > 0) {  // (memcmp of an empty table's null data is undefined)
      EXPECT_EQ(std::memcmp(back.data().data(), t.data().data(), t.data().size() * sizeof(double)), 0) << rows;
    }
    fs::remove(file);
  }
}

}  // namespace
}  // namespace rigid::io
