#pragma once
// Reading a bag's topics table, and checking every message belongs to one of them.

#include <vector>

#include "sqlite_db.h"
#include "teleop/bag/bag_types.h"

namespace teleop::bag {

/// The topics ordered by id; throws BagError unless the ids are 1..N (topics[id - 1]).
std::vector<TopicInfo> read_topics(SqliteDb& db);

/// Throws BagError naming the first message whose topic id has no topic.
void check_message_topics(SqliteDb& db);

}  // namespace teleop::bag
