#include "sqlite_db.h"

#include <utility>

namespace teleop::bag {
namespace {

// what a result code means for someone holding a bag, in words
std::string describe(int rc) {
  switch (rc & 0xff) {
    case SQLITE_FULL:
      return "disk full";
    case SQLITE_CORRUPT:
      return "the database is corrupt";
    case SQLITE_NOTADB:
      return "not an SQLite database (or its header is damaged)";
    case SQLITE_IOERR:
      return "I/O error";
    case SQLITE_CANTOPEN:
      return "cannot open the file";
    case SQLITE_READONLY:
      return "read-only";
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return "locked by another process";
    default:
      return "failed";
  }
}

int open_flags(SqliteDb::Mode mode) {
  return mode == SqliteDb::Mode::kCreate ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE : SQLITE_OPEN_READONLY;
}

}  // namespace

SqliteDb::SqliteDb(std::string path, Mode mode) : path_(std::move(path)) {
  const int rc = sqlite3_open_v2(path_.c_str(), &db_, open_flags(mode), nullptr);
  if (rc != SQLITE_OK) {
    // the handle exists even when opening failed (unless out of memory) and must be closed
    const std::string message = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    throw BagError(path_ + ": opening the database: " + describe(rc) + " (" + message + ")");
  }
  // a reader opened while the recorder commits waits for it instead of failing
  sqlite3_busy_timeout(db_, 2000);
}

SqliteDb::~SqliteDb() { sqlite3_close(db_); }

void SqliteDb::exec(const std::string& sql, const std::string& what) {
  const int rc = sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr);
  if (rc != SQLITE_OK) fail(rc, what);
}

void SqliteDb::exec_quietly(const std::string& sql) noexcept {
  sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr);
}

BagError SqliteDb::error(int rc, const std::string& what) const {
  return BagError(path_ + ": " + what + ": " + describe(rc) + " (" + sqlite3_errmsg(db_) + ")");
}

void SqliteDb::fail(int rc, const std::string& what) const { throw error(rc, what); }

SqliteStatement::SqliteStatement(SqliteDb& db, const std::string& sql) : db_(db) {
  const int rc = sqlite3_prepare_v2(db_.handle(), sql.c_str(), -1, &stmt_, nullptr);
  if (rc != SQLITE_OK) db_.fail(rc, "preparing \"" + sql + "\"");
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(stmt_); }

void SqliteStatement::bind(int index, int64_t value) {
  const int rc = sqlite3_bind_int64(stmt_, index, value);
  if (rc != SQLITE_OK) db_.fail(rc, "binding a value");
}

void SqliteStatement::bind(int index, const std::string& text) {
  const int rc = sqlite3_bind_text(stmt_, index, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) db_.fail(rc, "binding a text");
}

void SqliteStatement::bind_blob(int index, const uint8_t* data, size_t size) {
  // an empty blob bound from a pointer would be NULL, which the NOT NULL column refuses
  const int rc =
      size == 0 ? sqlite3_bind_zeroblob(stmt_, index, 0) : sqlite3_bind_blob64(stmt_, index, data, size, SQLITE_STATIC);
  if (rc != SQLITE_OK) db_.fail(rc, "binding a blob of " + std::to_string(size) + " bytes");
}

bool SqliteStatement::step(const std::string& what) {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  BagError error = db_.error(rc, what);  // before the reset, which may change the message
  sqlite3_reset(stmt_);
  throw error;
}

void SqliteStatement::run(const std::string& what) {
  step(what);
  reset();
}

void SqliteStatement::reset() noexcept { sqlite3_reset(stmt_); }

int64_t SqliteStatement::column_int64(int col) const { return sqlite3_column_int64(stmt_, col); }

bool SqliteStatement::column_is_null(int col) const { return sqlite3_column_type(stmt_, col) == SQLITE_NULL; }

std::string SqliteStatement::column_text(int col) const {
  const auto* text = sqlite3_column_text(stmt_, col);
  return text ? std::string(reinterpret_cast<const char*>(text), static_cast<size_t>(sqlite3_column_bytes(stmt_, col)))
              : std::string();
}

const uint8_t* SqliteStatement::column_blob(int col) const {
  return static_cast<const uint8_t*>(sqlite3_column_blob(stmt_, col));
}

size_t SqliteStatement::column_bytes(int col) const { return static_cast<size_t>(sqlite3_column_bytes(stmt_, col)); }

}  // namespace teleop::bag
