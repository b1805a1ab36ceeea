#pragma once
// A thin RAII layer over the SQLite C API whose every failure is a BagError naming the file.

#include <sqlite3.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "teleop/bag/bag_error.h"

namespace teleop::bag {

/// An open connection to one database file.
class SqliteDb {
 public:
  enum class Mode { kCreate, kReadOnly };

  SqliteDb(std::string path, Mode mode);
  ~SqliteDb();
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;

  /// Runs SQL that returns no rows (several statements allowed); `what` names the step in errors.
  void exec(const std::string& sql, const std::string& what);
  /// Runs SQL ignoring failures (rolling back after an error, best-effort tidying).
  void exec_quietly(const std::string& sql) noexcept;
  /// The error for result code `rc` while doing `what`:
  /// "<file>: <what>: disk full (database or disk is full)".
  BagError error(int rc, const std::string& what) const;
  /// Throws error(rc, what).
  [[noreturn]] void fail(int rc, const std::string& what) const;

  sqlite3* handle() const { return db_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

/// A prepared statement of one connection. A statement is reset before it is bound again.
class SqliteStatement {
 public:
  SqliteStatement(SqliteDb& db, const std::string& sql);
  ~SqliteStatement();
  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  void bind(int index, int64_t value);
  void bind(int index, const std::string& text);
  /// Binds `size` bytes that must stay valid until the statement is stepped.
  void bind_blob(int index, const uint8_t* data, size_t size);

  /// Steps once: true when a row is ready, false when done. Throws naming `what`.
  bool step(const std::string& what);
  /// Steps a statement that returns no rows, then resets it.
  void run(const std::string& what);
  void reset() noexcept;

  int64_t column_int64(int col) const;
  bool column_is_null(int col) const;
  std::string column_text(int col) const;
  /// A blob column: ask for its bytes after the pointer (SQLite's rule).
  const uint8_t* column_blob(int col) const;
  size_t column_bytes(int col) const;

 private:
  SqliteDb& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace teleop::bag
