#pragma once
// The io::InputError a reader throws, for tests that check what it names.
#include <gtest/gtest.h>

#include <string>

#include "io/input_error.hpp"

namespace rigflex::test {

// Calls `read` and returns the io::InputError it throws; fails the test,
// naming `what` (the file or the text read), if it throws none.
template <typename Read>
io::InputError input_error_of(Read&& read, const std::string& what) {
  try {
    read();
  } catch (const io::InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for " << what;
  return io::InputError("", 0, "", "");
}

}  // namespace rigflex::test
