#include "h5_handle.hpp"

#include <cstring>

namespace flagsim::data::h5 {

void silence_library_errors() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

Handle utf8_string_type() {
  Handle type = datatype(H5Tcopy(H5T_C_S1));
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  return type;
}

namespace {

// Opens `name` on `object` for writing, replacing an attribute of another shape.
Handle fresh_attribute(hid_t object, const char* name, hid_t type, hid_t space) {
  if (H5Aexists(object, name) > 0) H5Adelete(object, name);
  return attribute(H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT));
}

}  // namespace

bool write_string_attribute(hid_t object, const char* name, const std::string& value) {
  Handle type = utf8_string_type();
  Handle space = dataspace(H5Screate(H5S_SCALAR));
  Handle attr = fresh_attribute(object, name, type.get(), space.get());
  const char* text = value.c_str();
  return attr.valid() && H5Awrite(attr.get(), type.get(), &text) >= 0;
}

bool write_string_list_attribute(hid_t object, const char* name,
                                 const std::vector<std::string>& values) {
  Handle type = utf8_string_type();
  const hsize_t count = values.size();
  Handle space = dataspace(H5Screate_simple(1, &count, nullptr));
  Handle attr = fresh_attribute(object, name, type.get(), space.get());
  std::vector<const char*> texts;
  texts.reserve(values.size());
  for (const std::string& v : values) texts.push_back(v.c_str());
  return attr.valid() && H5Awrite(attr.get(), type.get(), texts.data()) >= 0;
}

bool write_int_attribute(hid_t object, const char* name, long long value) {
  Handle space = dataspace(H5Screate(H5S_SCALAR));
  Handle attr = fresh_attribute(object, name, H5T_STD_I64LE, space.get());
  return attr.valid() && H5Awrite(attr.get(), H5T_NATIVE_LLONG, &value) >= 0;
}

bool write_double_attribute(hid_t object, const char* name, double value) {
  Handle space = dataspace(H5Screate(H5S_SCALAR));
  Handle attr = fresh_attribute(object, name, H5T_IEEE_F64LE, space.get());
  return attr.valid() && H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, &value) >= 0;
}

bool read_string_attribute(hid_t object, const char* name, std::string& value) {
  if (H5Aexists(object, name) <= 0) return false;
  Handle attr = attribute(H5Aopen(object, name, H5P_DEFAULT));
  Handle type = datatype(H5Aget_type(attr.get()));
  if (H5Tget_class(type.get()) != H5T_STRING) return false;
  Handle space = dataspace(H5Aget_space(attr.get()));
  if (H5Sget_simple_extent_npoints(space.get()) != 1) return false;
  if (H5Tis_variable_str(type.get()) > 0) {
    Handle memory = utf8_string_type();
    char* text = nullptr;
    if (H5Aread(attr.get(), memory.get(), &text) < 0 || !text) return false;
    value = text;
    H5free_memory(text);
    return true;
  }
  const std::size_t size = H5Tget_size(type.get());
  std::vector<char> buffer(size + 1, '\0');
  if (H5Aread(attr.get(), type.get(), buffer.data()) < 0) return false;
  value.assign(buffer.data(), strnlen(buffer.data(), size));
  return true;
}

bool read_string_list_attribute(hid_t object, const char* name, std::vector<std::string>& values) {
  if (H5Aexists(object, name) <= 0) return false;
  Handle attr = attribute(H5Aopen(object, name, H5P_DEFAULT));
  Handle type = datatype(H5Aget_type(attr.get()));
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) <= 0) return false;
  Handle space = dataspace(H5Aget_space(attr.get()));
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) return false;
  std::vector<char*> texts(std::size_t(count), nullptr);
  Handle memory = utf8_string_type();
  if (H5Aread(attr.get(), memory.get(), texts.data()) < 0) return false;
  values.clear();
  for (char* text : texts) {
    values.emplace_back(text ? text : "");
    H5free_memory(text);
  }
  return true;
}

bool read_int_attribute(hid_t object, const char* name, long long& value) {
  if (H5Aexists(object, name) <= 0) return false;
  Handle attr = attribute(H5Aopen(object, name, H5P_DEFAULT));
  Handle type = datatype(H5Aget_type(attr.get()));
  if (H5Tget_class(type.get()) != H5T_INTEGER) return false;
  return H5Aread(attr.get(), H5T_NATIVE_LLONG, &value) >= 0;
}

bool read_double_attribute(hid_t object, const char* name, double& value) {
  if (H5Aexists(object, name) <= 0) return false;
  Handle attr = attribute(H5Aopen(object, name, H5P_DEFAULT));
  Handle type = datatype(H5Aget_type(attr.get()));
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) return false;
  return H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &value) >= 0;
}

}  // namespace flagsim::data::h5
