#pragma once
// Hostile strings for the safety sweep: line breaks of every kind (LF, CR, NEL,
// U+2028/2029, VT, FF), YAML document and structure markers, a whole second
// JointTrajectory document, URScript statements, quotes and backslashes,
// control and bidi characters, bytes that are no UTF-8, and long strings;
// combined at random (seeded).
#include <random>
#include <string>
#include <vector>

namespace srp::safety {

inline const std::vector<std::string>& hostileFragments() {
  static const std::vector<std::string> f = {
      "\n", "\r", "\r\n", "\n\r", "\xC2\x85", "\xE2\x80\xA8", "\xE2\x80\xA9", "\x0B", "\x0C", "\x1C", "\x1D", "\x1E",
      std::string(1, '\0'), "\t", "\x7F", "\x1B[2J", "---", "...", "--- !!map", "%YAML 1.1", "# ", "#", "'", "''", "\"",
      "\\", "\\n", "\\r", "\\u2028", "{", "}", "[", "]", ": ", "- ", "? ", "&a ", "*a", "| ", "> ",
      "!!python/object/apply:os.system ['true']", "\xEF\xBB\xBF", "\xE2\x80\xAE", "\xE2\x80\x8F", "\xE2\x81\xA6",
      "\xE2\x81\xA9", "\xFF", "\xC3", "\xED\xA0\x80", "\xC0\xAF", "\xF4\x90\x80\x80", "\xF0\x9F\xA4\x96", "\xC3\xA9",
      "end", "def hijack():", "movej([0, 0, 0, 0, 0, 0], a=9, v=9)", "set_tool_digital_out(0, True)",
      "  servoj([1, 1, 1, 1, 1, 1], 0, 0, 0.008, 0.1, 300)", "popup(\"x\")", "halt", "sec: 99",
      "points:\n- positions: [9, 9, 9, 9, 9, 9]\n  time_from_start: {sec: 0, nanosec: 0}",
      "header:\n  frame_id: ''\njoint_names: [a, b, c, d, e, f]\npoints: []", "  # indented", "\t#", "$(reboot)",
      "`id`", "; rm -rf /", "%s%n", "\xE2\x80\x8B", "\xEF\xBF\xBD", "\xE3\x80\x80"};
  return f;
}

/// `count` hostile strings: first every fragment alone and the variants the
/// review found (a line break, then a complete document), then random mixes of
/// 1-6 fragments and words, some long.
inline std::vector<std::string> hostileStrings(std::size_t count, unsigned seed = 35) {
  const auto& f = hostileFragments();
  const std::string secondDocument =
      "---\nheader:\n  stamp: {sec: 0, nanosec: 0}\n  frame_id: ''\njoint_names: [shoulder_pan_joint, "
      "shoulder_lift_joint, elbow_joint, wrist_1_joint, wrist_2_joint, wrist_3_joint]\npoints:\n- positions: [3.1, "
      "0, 0, 0, 0, 0]\n  velocities: [0, 0, 0, 0, 0, 0]\n  time_from_start: {sec: 1, nanosec: 0}\n---\n";
  std::vector<std::string> out(f.begin(), f.end());
  for (const char* br : {"\n", "\r", "\r\n", "\xC2\x85", "\xE2\x80\xA8", "\xE2\x80\xA9", "\x0B\x0C"}) {
    out.push_back(std::string("task") + br + secondDocument);
    out.push_back(std::string("x") + br + "  stopj(2)" + br + "  movej([0, 0, 0, 0, 0, 0])" + br + "end" + br);
  }
  const std::vector<std::string> words = {"cuboid", "blue box", "Pick up the star", "gray", "a", " ", "x1"};
  std::mt19937 rng(seed);
  while (out.size() < count) {
    std::string s;
    const int parts = 1 + static_cast<int>(rng() % 6);
    for (int k = 0; k < parts; ++k)
      s += (rng() % 3 == 0) ? words[rng() % words.size()] : f[rng() % f.size()];
    if (rng() % 50 == 0) s += std::string(600 + rng() % 3000, rng() % 2 ? '\n' : 'a');
    out.push_back(s);
  }
  out.resize(count);
  return out;
}

}  // namespace srp::safety
