#include "srp/core/ObjectCatalogue.h"

#include <set>

#include "srp/core/DataPaths.h"
#include "srp/core/Error.h"

namespace srp::core {
ObjectCatalogue::ObjectCatalogue(std::vector<ObjectClass> classes) : classes_(std::move(classes)) {
  std::set<std::string> names;
  std::set<int> ids;
  for (const auto& c : classes_) {
    if (!names.insert(c.name).second) throw InvalidInputError("catalogue: duplicate class name '" + c.name + "'");
    if (!ids.insert(c.classId).second)
      throw InvalidInputError("catalogue: duplicate class_id " + std::to_string(c.classId) + " ('" + c.name + "')");
  }
}

std::string ObjectCatalogue::defaultPath() { return DataPaths::file("datasets/kb/catalogue.json").string(); }

const ObjectClass* ObjectCatalogue::find(const std::string& name) const {
  for (const auto& c : classes_)
    if (c.name == name) return &c;
  return nullptr;
}

const ObjectClass* ObjectCatalogue::findById(int classId) const {
  for (const auto& c : classes_)
    if (c.classId == classId) return &c;
  return nullptr;
}

const ObjectClass* ObjectCatalogue::ground(const std::string& noun, const std::string& colour) const {
  if (!colour.empty())
    if (const ObjectClass* c = find(colour + " " + noun)) return c;
  if (const ObjectClass* c = find(noun)) return c;
  const ObjectClass* match = nullptr;
  int count = 0;
  for (const auto& c : classes_) {
    if (c.noun != noun) continue;
    if (!colour.empty() && c.colourName == colour) return &c;
    match = &c;
    ++count;
  }
  return (count == 1 && colour.empty()) ? match : nullptr;
}

const ObjectClass& ObjectCatalogue::at(const std::string& name) const {
  if (const ObjectClass* c = find(name)) return *c;
  std::string known;
  for (const auto& c : classes_) known += (known.empty() ? "" : ", ") + c.name;
  throw InvalidInputError("unknown object class '" + name + "' (the catalogue knows: " + known + ")");
}

std::string toString(ObjectKind kind) { return kind == ObjectKind::Part ? "part" : "container"; }

}  // namespace srp::core
