#pragma once
// Test helpers: the message of the exception of a given type a callable throws.
#include <exception>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"

namespace sacfuse::testing {

// The message of the `ErrorType` `fn` throws ("" and a test failure when it throws nothing or another type).
template <typename ErrorType, typename Fn>
std::string ErrorOf(Fn fn) {
  try {
    fn();
  } catch (const ErrorType& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not the expected error type: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no exception";
  return "";
}

template <typename Fn>
std::string InputErrorOf(Fn fn) {
  return ErrorOf<InputError>(fn);
}

// For option validators: the ConfigError's message.
template <typename Fn>
std::string OptionErrorOf(Fn fn) {
  return ErrorOf<ConfigError>(fn);
}

}  // namespace sacfuse::testing
