#pragma once
// What the HDF5 writer and reader share (formats/hdf5_table.cpp, formats/hdf5_table_reader.cpp): a handle
// that closes itself, and HDF5's own error printing turned off (pkm reports its own messages, naming the
// file).
#include <hdf5.h>

#include <string>

namespace pkm::formats {

/// HDF5 prints its error stack to stderr by default; pkm reports its own message instead.
inline void quiet_hdf5_errors() {
  static const bool quiet = [] { return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0; }();
  (void)quiet;
}

/// Closes an HDF5 handle of any kind when it leaves scope.
class Hdf5Handle {
 public:
  explicit Hdf5Handle(hid_t id) : id_(id) {}
  ~Hdf5Handle() {
    if (id_ >= 0) H5Idec_ref(id_);
  }
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
};

// The string attribute `name` of `owner` (variable-length, as write_string_attribute writes it).
inline bool read_hdf5_string_attribute(hid_t owner, const char* name, std::string& out) {
  const Hdf5Handle attribute(H5Aopen(owner, name, H5P_DEFAULT));
  if (!attribute.valid()) return false;
  const Hdf5Handle type(H5Aget_type(attribute.get()));
  if (!type.valid() || H5Tis_variable_str(type.get()) <= 0) return false;
  char* text = nullptr;
  if (H5Aread(attribute.get(), type.get(), &text) < 0) return false;
  out = text != nullptr ? text : "";
  const Hdf5Handle space(H5Aget_space(attribute.get()));
  H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, &text);
  return true;
}

}  // namespace pkm::formats
