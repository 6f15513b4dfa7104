// Internal helpers of the HDF5 writer and reader (io/h5): HDF5 error text, the saved error of a
// failed call, object paths, string types and dataspaces. Not part of the io/h5 interface.
#pragma once

#include <hdf5.h>

#include <string>
#include <vector>

#include "io/h5/h5_handle.hpp"

namespace raceway::h5 {

/// The first (API-level) and the last (innermost) message of the current HDF5 error stack.
std::string error_text();

/// The error stack of the first failed HDF5 call of the current operation: helpers save it
/// (failed()) before their cleanup calls (H5?close) clear the stack.
std::string& saved_error();
/// Saves the current error stack (if none is saved yet) and returns false.
bool failed();
/// failed(), returning the invalid id -1.
hid_t failed_id();

/// HDF5's error printing off for one operation, which starts with no saved error.
class ErrorSilencer : public QuietErrors {
 public:
  ErrorSilencer() { saved_error().clear(); }
};

/// "/a//b/" -> {"a", "b"}
std::vector<std::string> split_path(const std::string& path);
/// "/" + the first `count` parts joined by "/" ("/" for none).
std::string join_path(const std::vector<std::string>& parts, std::size_t count);
/// The canonical form "/a/b" of an object path.
std::string normalize(const std::string& path);

/// Variable-length UTF-8 string type (h5py reads it as str); -1 on failure.
hid_t make_vlen_string_type();
/// A simple dataspace of `dims` (empty: scalar), optionally with maximum dimensions.
hid_t make_dataspace(const std::vector<hsize_t>& dims, const std::vector<hsize_t>* max_dims = nullptr);

/// Creates the groups parts[0..count) that do not exist yet (no timestamps: reproducible files).
bool ensure_groups(hid_t file, const std::vector<std::string>& parts, std::size_t count);
/// Replaces attribute `name` on obj (buf == nullptr: zero elements, nothing written).
bool write_attribute(hid_t obj, const std::string& name, hid_t file_type, hid_t mem_type, hid_t space,
                     const void* buf);
bool write_string_attribute(hid_t obj, const std::string& name, const std::string& value);
bool write_units_description(hid_t obj, const std::string& units, const std::string& description);
/// A dataset creation property list without timestamps (reproducible files); -1 on failure.
hid_t make_dcpl();
/// Whether a link `path` exists in the file (missing parents: false); -1 on an HDF5 error.
int link_exists(hid_t file, const std::string& path);

/// Reserves `bytes` of disk after the end of the file at `path` (fallocate, FALLOC_FL_KEEP_SIZE: its
/// size does not change), so that a write finds a full disk (or a file-size limit) before it
/// writes anything. "" when reserved or when the file system cannot reserve; else the system's reason.
std::string reserve_disk(const std::string& path, std::size_t bytes);

}  // namespace raceway::h5
