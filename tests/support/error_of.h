#pragma once
// Test helper: the message of the InputError a callable throws.
#include <exception>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse::testing {

// The message of the InputError `fn` throws ("" and a test failure when it throws nothing or another type).
template <typename Fn>
std::string InputErrorOf(Fn fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no exception";
  return "";
}

}  // namespace sacfuse::testing
