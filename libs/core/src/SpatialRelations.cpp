#include "srp/core/SpatialRelations.h"

#include <algorithm>
#include <iterator>

namespace srp::core {

bool isNeighbourRelation(const std::string& r) {
  static const char* kWords[] = {"next to", "beside", "adjacent to", "adjacent", "near", "alongside",
                                 "by", "close to", "nearby", "next"};
  return std::any_of(std::begin(kWords), std::end(kWords), [&](const char* w) { return r == w; });
}

bool isContainmentRelation(const std::string& r) {
  static const char* kWords[] = {"in", "into", "inside", "on", "onto", "to", "back to", "at", "within", "in to"};
  return std::any_of(std::begin(kWords), std::end(kWords), [&](const char* w) { return r == w; });
}

}  // namespace srp::core
