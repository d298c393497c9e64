#include "srp/core/Text.h"

#include <utility>

namespace srp::core {

std::string toLowerAscii(std::string text) {
  for (char& c : text)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return text;
}

std::string normaliseName(std::string name) {
  name = toLowerAscii(std::move(name));
  for (char& c : name)
    if (c == '_' || c == '-') c = ' ';
  const auto b = name.find_first_not_of(' '), e = name.find_last_not_of(' ');
  return b == std::string::npos ? "" : name.substr(b, e - b + 1);
}

}  // namespace srp::core
