// The message of the refx::Error a call throws, for tests that check error texts.
#pragma once
#include <string>
#include <string_view>

#include "refx/core/diagnostics.h"

namespace refx::test {

// What `f()` throws as refx::Error; "(no error)" when it returns.
template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace refx::test
