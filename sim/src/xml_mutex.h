#pragma once
// MuJoCo 2.2's XML parser, compiler and "last loaded XML" are global state: every use of them in
// this library (loading, flattening) holds this one mutex.

#include <mutex>

namespace teleop::sim {

std::mutex& xml_mutex();

}  // namespace teleop::sim
