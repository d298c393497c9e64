#pragma once
// Test helper: the call throws an error of type E whose message contains `needle`.

#include <gtest/gtest.h>

#include <string>

namespace srp::calib::test {

template <typename E, typename Fn>
void expectErrorNaming(Fn fn, const std::string& needle) {
  try {
    fn();
    ADD_FAILURE() << "expected an error naming '" << needle << "'";
  } catch (const E& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

}  // namespace srp::calib::test
