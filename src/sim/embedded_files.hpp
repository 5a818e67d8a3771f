// Files built into the tool (cmake/embed_files.cmake): the example programs under examples/, so that
// `trionet ring simulate example1` runs them from any directory, installed or not.
#pragma once

#include <cstddef>
#include <string_view>

#include "trionet/span.hpp"

namespace trionet::host {

struct embedded_file {
  const char* path;  ///< relative to the source tree, e.g. "examples/manual/example1.bas"
  const unsigned char* data;
  std::size_t size;
  std::string_view text() const noexcept { return {reinterpret_cast<const char*>(data), size}; }
};

span<const embedded_file> embedded_files() noexcept;

/// The file built in as `path`, or nullptr.
inline const embedded_file* find_embedded_file(std::string_view path) noexcept {
  for (const embedded_file& f : embedded_files()) {
    if (path == f.path) return &f;
  }
  return nullptr;
}

}  // namespace trionet::host
