#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rigid::io {

/// A rectangular table of doubles with named columns, stored row-major: the shape of
/// a trajectory (one row per output time).
/// Class invariant: data().size() == rows() * columns().size(); column names are
/// unique and non-empty.
class Table {
 public:
  /// @throws rigid::Error if a name is empty or repeated.
  explicit Table(std::vector<std::string> columns);

  /// Appends one row. @throws rigid::Error if row.size() differs from the column count.
  void add_row(std::span<const double> row);
  /// Makes room for `rows` rows in all (no row is added).
  void reserve_rows(std::size_t rows) { data_.reserve(rows * columns_.size()); }

  [[nodiscard]] const std::vector<std::string>& columns() const { return columns_; }
  [[nodiscard]] std::size_t rows() const { return columns_.empty() ? 0 : data_.size() / columns_.size(); }
  [[nodiscard]] const std::vector<double>& data() const { return data_; }
  [[nodiscard]] double operator()(std::size_t row, std::size_t col) const {
    return data_[row * columns_.size() + col];
  }
  /// Index of the column called `name`. @throws rigid::Error listing the columns if absent.
  [[nodiscard]] std::size_t column(std::string_view name) const;
  /// The columns at `indices`, in that order, with every row.
  /// @throws rigid::Error for an index out of range or repeated.
  [[nodiscard]] Table select(std::span<const std::size_t> indices) const;

 private:
  std::vector<std::string> columns_;
  std::vector<double> data_;
};

/// CSV text: a header line of column names, then one line per row; every double is
/// printed in its shortest form that reads back to the same bits. With `threads` > 1, a table
/// of many rows (4096 or more a thread) is formatted in blocks on that many threads: the same
/// text.
[[nodiscard]] std::string to_csv(const Table& table, std::size_t threads = 1);

/// CSV text of `table` with one column of text after its numbers (a sweep's `error`): `name`
/// in the header and `text[r]` on row r, quoted as RFC 4180 says (in double quotes, a quote
/// doubled) when it holds a comma, a quote or a line break; an empty text is an empty field.
/// `threads` as above.
/// @throws rigid::Error if text.size() differs from table.rows() or `name` is empty.
[[nodiscard]] std::string to_csv(const Table& table, std::string_view name, std::span<const std::string> text,
                                 std::size_t threads = 1);

/// NumPy .npy (format 1.0) bytes: a little-endian float64 array of shape (rows, columns),
/// C order. Column names are not stored; they are the CSV header.
[[nodiscard]] std::string to_npy(const Table& table);

/// Writes to_csv(table) / to_npy(table) atomically (see write_file_atomically).
void write_csv(const std::filesystem::path& path, const Table& table);
void write_npy(const std::filesystem::path& path, const Table& table);

/// Reads a CSV written by write_csv (or any numeric CSV with a header line).
/// @throws rigid::Error with file:line:column for a missing file, a ragged row or a
///         field that is not a number.
[[nodiscard]] Table read_csv(const std::filesystem::path& path);

}  // namespace rigid::io
