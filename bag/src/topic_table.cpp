#include "topic_table.h"

#include <string>

namespace teleop::bag {

std::vector<TopicInfo> read_topics(SqliteDb& db) {
  SqliteStatement query(db, "SELECT id, name, type, offered_qos_profiles FROM topics ORDER BY id");
  std::vector<TopicInfo> topics;
  while (query.step("reading the topics")) {
    TopicInfo topic;
    topic.name = query.column_text(1);
    topic.type = query.column_text(2);
    topic.qos_profile = query.column_text(3);
    const int64_t id = query.column_int64(0);
    // a topic is found by its index: ids with gaps (a topic deleted by hand) are not read
    if (id != static_cast<int64_t>(topics.size()) + 1) {
      throw BagError(db.path() + ": topic " + topic.name + " has id " + std::to_string(id) + ", expected " +
                     std::to_string(topics.size() + 1) + " (topic ids must be 1..N)");
    }
    topics.push_back(std::move(topic));
  }
  return topics;
}

void check_message_topics(SqliteDb& db) {
  SqliteStatement query(db, "SELECT id, topic_id FROM messages WHERE topic_id NOT IN (SELECT id FROM topics) LIMIT 1");
  if (query.step("checking the messages' topics")) {
    throw BagError(db.path() + ": message " + std::to_string(query.column_int64(0)) + " has topic id " +
                   std::to_string(query.column_int64(1)) + ", which has no topic");
  }
}

}  // namespace teleop::bag
