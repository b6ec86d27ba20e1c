#pragma once
// RAII ownership of HDF5 C API identifiers, and small helpers around them.
#include <hdf5.h>

#include <string>
#include <utility>
#include <vector>

namespace flagsim::data::h5 {

/// Owns one hid_t and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept { *this = std::move(other); }
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      std::swap(id_, other.id_);
      std::swap(closer_, other.closer_);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0 && closer_) closer_(id_);
    id_ = -1;
  }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

inline Handle file(hid_t id) {
  return {id, H5Fclose};
}
inline Handle group(hid_t id) {
  return {id, H5Gclose};
}
inline Handle dataset(hid_t id) {
  return {id, H5Dclose};
}
inline Handle dataspace(hid_t id) {
  return {id, H5Sclose};
}
inline Handle attribute(hid_t id) {
  return {id, H5Aclose};
}
inline Handle datatype(hid_t id) {
  return {id, H5Tclose};
}
inline Handle plist(hid_t id) {
  return {id, H5Pclose};
}

/// Silences HDF5's own error stack printing: we report errors ourselves.
void silence_library_errors();

/// Variable-length UTF-8 string type (h5py reads it as str).
Handle utf8_string_type();

/// Scalar string attribute on `object`, created or overwritten. False on failure.
bool write_string_attribute(hid_t object, const char* name, const std::string& value);
/// 1D attribute of strings.
bool write_string_list_attribute(hid_t object, const char* name,
                                 const std::vector<std::string>& values);
bool write_int_attribute(hid_t object, const char* name, long long value);
bool write_double_attribute(hid_t object, const char* name, double value);

/// Reads a scalar string attribute (variable or fixed length); false if absent or not a string.
bool read_string_attribute(hid_t object, const char* name, std::string& value);
bool read_string_list_attribute(hid_t object, const char* name, std::vector<std::string>& values);
bool read_int_attribute(hid_t object, const char* name, long long& value);
bool read_double_attribute(hid_t object, const char* name, double& value);

}  // namespace flagsim::data::h5
