#include "rigid/io/table.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdint>
#include <exception>
#include <fstream>
#include <sstream>
#include <thread>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "rigid/common/error.hpp"
#include "rigid/common/escape.hpp"
#include "rigid/io/atomic_file.hpp"

namespace rigid::io {

Table::Table(std::vector<std::string> columns) : columns_(std::move(columns)) {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    RIGID_REQUIRE(!columns_[i].empty(), "column {} has an empty name", i);
    RIGID_REQUIRE(std::find(columns_.begin(), columns_.begin() + static_cast<std::ptrdiff_t>(i),
                            columns_[i]) == columns_.begin() + static_cast<std::ptrdiff_t>(i),
                  "column name '{}' appears twice", columns_[i]);
  }
}

void Table::add_row(std::span<const double> row) {
  RIGID_REQUIRE(row.size() == columns_.size(), "row has {} values, expected {} (one per column)",
                row.size(), columns_.size());
  data_.insert(data_.end(), row.begin(), row.end());
}

Table Table::select(std::span<const std::size_t> indices) const {
  std::vector<std::string> names;
  names.reserve(indices.size());
  for (const std::size_t c : indices) {
    RIGID_REQUIRE(c < columns_.size(), "column index {} is out of range; the table has {} columns",
                  c, columns_.size());
    names.push_back(columns_[c]);
  }
  Table out(std::move(names));  // refuses a repeated column
  const std::size_t n = columns_.size(), count = rows();
  out.data_.reserve(count * indices.size());
  for (std::size_t r = 0; r < count; ++r) {
    for (const std::size_t c : indices) out.data_.push_back(data_[r * n + c]);
  }
  return out;
}

std::size_t Table::column(std::string_view name) const {
  const auto it = std::find(columns_.begin(), columns_.end(), name);
  RIGID_REQUIRE(it != columns_.end(), "no column '{}'; the columns are {}", name,
                fmt::join(columns_, ", "));
  return static_cast<std::size_t>(it - columns_.begin());
}

namespace {

// A CSV field of text: as it is, or in double quotes with each quote doubled (RFC 4180) when
// it holds a character that would end the field.
void append_text_field(fmt::memory_buffer& out, std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
    out.append(text);
    return;
  }
  out.push_back('"');
  for (const char c : text) {
    if (c == '"') out.push_back('"');
    out.push_back(c);
  }
  out.push_back('"');
}

// The lines of rows [begin, end), each ended by '\n'.
void append_csv_rows(fmt::memory_buffer& out, const Table& table, std::span<const std::string> text, bool with_text,
                     std::size_t begin, std::size_t end) {
  const std::size_t n = table.columns().size();
  for (std::size_t r = begin; r < end; ++r) {
    for (std::size_t c = 0; c < n; ++c) {
      // fmt's "{}" for double is the shortest representation that round-trips; compiled, so
      // that the format string is not parsed again for each of a table's numbers
      fmt::format_to(fmt::appender(out), FMT_COMPILE("{}"), table(r, c));
      if (c + 1 < n) out.push_back(',');
    }
    if (with_text) {
      if (n > 0) out.push_back(',');
      append_text_field(out, text[r]);
    }
    out.push_back('\n');
  }
}

std::string csv_text(const Table& table, std::string_view name, std::span<const std::string> text, bool with_text,
                     std::size_t threads) {
  fmt::memory_buffer head;
  fmt::format_to(fmt::appender(head), "{}", fmt::join(table.columns(), ","));
  if (with_text) fmt::format_to(fmt::appender(head), "{}{}", table.columns().empty() ? "" : ",", name);
  head.push_back('\n');
  // a sweep's runs.csv is written after its runs, serially but for this: the rows in as many
  // blocks as threads, each formatted by its own (the same text as one block; below 4096 rows
  // a thread costs more than it saves)
  constexpr std::size_t kRowsPerThread = 4096;
  const std::size_t rows = table.rows();
  const std::size_t blocks = std::clamp<std::size_t>(std::min(threads, rows / kRowsPerThread), 1, 256);
  std::vector<fmt::memory_buffer> parts(blocks);
  std::vector<std::exception_ptr> failed(blocks);  // a block's bad_alloc, thrown here
  {
    std::vector<std::jthread> pool;
    for (std::size_t b = 1; b < blocks; ++b) {
      pool.emplace_back([&, b] {
        try {
          append_csv_rows(parts[b], table, text, with_text, rows * b / blocks, rows * (b + 1) / blocks);
        } catch (...) {
          failed[b] = std::current_exception();
        }
      });
    }
    append_csv_rows(parts[0], table, text, with_text, 0, rows / blocks);
  }  // joined
  for (const auto& f : failed) {
    if (f) std::rethrow_exception(f);
  }
  std::string out(head.data(), head.size());
  std::size_t total = out.size();
  for (const auto& p : parts) total += p.size();
  out.reserve(total);
  for (const auto& p : parts) out.append(p.data(), p.size());
  return out;
}

}  // namespace

std::string to_csv(const Table& table, std::size_t threads) { return csv_text(table, {}, {}, false, threads); }

std::string to_csv(const Table& table, std::string_view name, std::span<const std::string> text, std::size_t threads) {
  RIGID_REQUIRE(!name.empty(), "the text column has an empty name");
  RIGID_REQUIRE(text.size() == table.rows(), "{} texts for a table of {} rows (one per row)", text.size(),
                table.rows());
  return csv_text(table, name, text, true, threads);
}

std::string to_npy(const Table& table) {
  static_assert(std::endian::native == std::endian::little, "the .npy writer assumes little endian");
  // NPY 1.0: magic, version, uint16 header length, a Python-literal dict padded with
  // spaces and ended by '\n' so that the data starts at a multiple of 64 bytes.
  std::string header = fmt::format("{{'descr': '<f8', 'fortran_order': False, 'shape': ({}, {}), }}",
                                   table.rows(), table.columns().size());
  const std::size_t preamble = 10;
  const std::size_t total = (preamble + header.size() + 1 + 63) / 64 * 64;
  header.append(total - preamble - header.size() - 1, ' ');
  header.push_back('\n');
  std::string out = "\x93NUMPY";
  out.push_back('\x01');
  out.push_back('\x00');
  const auto len = static_cast<std::uint16_t>(header.size());
  out.push_back(static_cast<char>(len & 0xff));
  out.push_back(static_cast<char>(len >> 8));
  out += header;
  const auto& d = table.data();
  out.append(reinterpret_cast<const char*>(d.data()), d.size() * sizeof(double));
  return out;
}

void write_csv(const std::filesystem::path& path, const Table& table) {
  write_file_atomically(path, to_csv(table));
}

void write_npy(const std::filesystem::path& path, const Table& table) {
  write_file_atomically(path, to_npy(table));
}

namespace {

std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

}  // namespace

Table read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  RIGID_REQUIRE(in.good(), "cannot open '{}' for reading", path.string());
  std::string line;
  RIGID_REQUIRE(static_cast<bool>(std::getline(in, line)),
                "'{}' is empty; expected a header line of column names", path.string());
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> names;
  int header_column = 1;
  for (auto f : split_commas(line)) {
    // the header's names, each once and none empty (Table's own check, here with the place)
    if (f.empty() || std::find(names.begin(), names.end(), f) != names.end()) {
      detail::throw_error_at({path.string(), 1, header_column},
                             f.empty() ? fmt::format("column {} of the header has an empty name; "
                                                     "expected a column name",
                                                     names.size() + 1)
                                       : fmt::format("column name '{}' appears twice in the "
                                                     "header; expected each name once",
                                                     escaped(f)));
    }
    // no control character (a carriage return inside a name would not survive a write and a
    // read: the line's last one is taken for a CRLF ending)
    if (const auto bad = std::find_if(f.begin(), f.end(), [](char c) {
          return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
        });
        bad != f.end()) {
      detail::throw_error_at({path.string(), 1, header_column + static_cast<int>(bad - f.begin())},
                             fmt::format("column name '{}' holds a control character; expected "
                                         "printable names",
                                         escaped(f)));
    }
    names.emplace_back(f);
    header_column += static_cast<int>(f.size()) + 1;
  }
  Table table(std::move(names));
  std::vector<double> row;
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const auto fields = split_commas(line);
    if (fields.size() != table.columns().size()) {
      detail::throw_error_at({path.string(), line_no, 1},
                             fmt::format("row has {} fields, expected {} (one per column)",
                                         fields.size(), table.columns().size()));
    }
    row.clear();
    int column = 1;
    for (auto f : fields) {
      double v = 0;
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
      if (ec != std::errc() || end != f.data() + f.size()) {
        detail::throw_error_at({path.string(), line_no, column},
                               fmt::format("'{}' is not a number", escaped(f)));
      }
      row.push_back(v);
      column += static_cast<int>(f.size()) + 1;
    }
    table.add_row(row);
  }
  return table;
}

}  // namespace rigid::io
