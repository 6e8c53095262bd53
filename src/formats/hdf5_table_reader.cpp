#include "formats/hdf5_table_reader.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <future>
#include <memory>
#include <stdexcept>

#include "formats/chunk_worker.hpp"
#include "formats/hdf5_chunk_filter.hpp"
#include "formats/hdf5_handle.hpp"

namespace pkm::formats {

namespace {

Error table_read_error(const std::string& path, const std::string& what) {
  Error e = make_error(ErrorCode::bad_input, fmt::format("{}: {}", path, what));
  e.location.file = path;
  return e;
}

// The links of `group` in the order they were made; by name when the file did not track that order.
bool column_names(hid_t group, std::vector<std::string>& names) {
  H5G_info_t info;
  if (H5Gget_info(group, &info) < 0) return false;
  unsigned flags = 0;
  const Hdf5Handle properties(H5Gget_create_plist(group));
  const bool tracked = properties.valid() && H5Pget_link_creation_order(properties.get(), &flags) >= 0 &&
                       (flags & H5P_CRT_ORDER_TRACKED) != 0;
  const H5_index_t index = tracked ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t size = H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (size < 0) return false;
    std::string name(static_cast<std::size_t>(size) + 1, '\0');
    if (H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, k, name.data(), name.size(), H5P_DEFAULT) < 0)
      return false;
    name.resize(static_cast<std::size_t>(size));
    names.push_back(std::move(name));
  }
  return true;
}

/// A column stored as Hdf5File writes them: chunked 1-D, shuffled then deflated, 64-bit little-endian doubles
/// or integers. Its chunks can be read raw and inflated off HDF5's thread (ChunkInflater).
bool stored_as_written(hid_t dataset, hsize_t& chunk_rows, bool& integer) {
  const Hdf5Handle properties(H5Dget_create_plist(dataset));
  if (!properties.valid() || H5Pget_layout(properties.get()) != H5D_CHUNKED) return false;
  if (H5Pget_chunk(properties.get(), 1, &chunk_rows) != 1 || H5Pget_nfilters(properties.get()) != 2)
    return false;
  const H5Z_filter_t expected[2] = {H5Z_FILTER_SHUFFLE, H5Z_FILTER_DEFLATE};
  for (unsigned k = 0; k < 2; ++k) {
    unsigned flags = 0, config = 0, values[8];
    std::size_t count = 8;
    if (H5Pget_filter2(properties.get(), k, &flags, &count, values, 0, nullptr, &config) != expected[k])
      return false;
  }
  const Hdf5Handle type(H5Dget_type(dataset));
  if (H5Tequal(type.get(), H5T_IEEE_F64LE) > 0) return integer = false, true;
  if (H5Tequal(type.get(), H5T_STD_I64LE) > 0) return integer = true, true;
  return false;
}

/// The next block of rows, its chunks read raw and inflated on the worker while the caller reads the block
/// before it.
struct BlockJob {
  long start = 0, size = 0;
  bool raw = false;  ///< false: a chunk HDF5 must read itself (a filter skipped, or not stored)
  std::vector<ChunkBytes> stored;
  std::vector<std::vector<double>> values;
  std::unique_ptr<ChunkInflater> inflater;
};

}  // namespace

struct Hdf5TableReader::State {
  std::string path, table;
  hid_t file = -1;
  std::vector<hid_t> datasets;
  std::vector<std::string> names, units;
  std::vector<std::vector<double>> block;  // the rows in memory, a vector per column
  long rows = 0, block_rows = 0, block_start = 0, block_size = 0, read = 0;
  /// Every column stored as Hdf5File writes them, with chunks of block_rows rows: blocks are whole chunks,
  /// read ahead on `worker`.
  bool chunks_raw = false;
  std::vector<bool> integer;
  BlockJob job;
  std::future<void> inflating;
  std::unique_ptr<ChunkWorker> worker;

  ~State() {
    if (inflating.valid()) inflating.wait();
    for (const hid_t d : datasets) H5Dclose(d);
    if (file >= 0) H5Fclose(file);
  }

  Error error(const std::string& what) const {
    return table_read_error(path, fmt::format("table {}: {}", table, what));
  }

  // Adds the column `name`: a 1-D dataset with a unit, as long as the others.
  Status add_column(hid_t group, const std::string& name) {
    const hid_t dataset = H5Dopen2(group, name.c_str(), H5P_DEFAULT);
    if (dataset < 0) return error(fmt::format("{} is not a column", name));
    datasets.push_back(dataset);
    const Hdf5Handle space(H5Dget_space(dataset));
    hsize_t length = 0;
    if (H5Sget_simple_extent_ndims(space.get()) != 1 ||
        H5Sget_simple_extent_dims(space.get(), &length, nullptr) < 0)
      return error(fmt::format("{} is not a column", name));
    if (datasets.size() > 1 && static_cast<long>(length) != rows)
      return error(fmt::format("{} has {} rows, {} {}", name, length, names.front(), rows));
    rows = static_cast<long>(length);
    std::string unit;
    read_hdf5_string_attribute(dataset, "unit", unit);  // a column without a unit reads as unitless
    names.push_back(name);
    units.push_back(std::move(unit));
    return ok_status();
  }

  // Reads the rows from `read` on, up to block_rows of them, of every column.
  Status read_block() {
    if (chunks_raw) return take_inflated_block();
    block_start = read;
    block_size = std::min(block_rows, rows - read);
    return read_through_hdf5(block);
  }

  // The rows from block_start on, block_size of them, of every column, through HDF5's own filters.
  Status read_through_hdf5(std::vector<std::vector<double>>& into) {
    const hsize_t start[1] = {static_cast<hsize_t>(block_start)},
                  count[1] = {static_cast<hsize_t>(block_size)};
    for (std::size_t c = 0; c < datasets.size(); ++c) {
      const Hdf5Handle file_space(H5Dget_space(datasets[c]));
      const Hdf5Handle memory_space(H5Screate_simple(1, count, nullptr));
      if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) < 0 ||
          H5Dread(datasets[c], H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT,
                  into[c].data()) < 0)
        return error(fmt::format("cannot read {} from row {}", names[c], block_start + 1));
    }
    return ok_status();
  }

  // The block read ahead (or, the first time, read now), then the next one handed to the worker.
  Status take_inflated_block() {
    if (!inflating.valid()) read_raw_block(read);
    try {
      if (inflating.valid()) inflating.get();
    } catch (const std::exception& e) {
      return error(fmt::format("cannot inflate the rows from {}: {}", job.start + 1, e.what()));
    }
    block_start = job.start;
    block_size = job.size;
    if (job.raw) {
      job.values.swap(block);
    } else if (Status read_here = read_through_hdf5(block); !read_here) {
      return read_here;
    }
    if (block_start + block_size < rows) read_raw_block(block_start + block_size);
    return ok_status();
  }

  // The stored chunks of the block from `start` (HDF5 is called on this thread only), inflated on the worker.
  void read_raw_block(long start) {
    job.start = start;
    job.size = std::min(block_rows, rows - start);
    job.raw = true;
    const hsize_t offset[1] = {static_cast<hsize_t>(start)};
    job.stored.resize(datasets.size());
    for (std::size_t c = 0; c < datasets.size() && job.raw; ++c) {
      hsize_t bytes = 0;
      std::uint32_t skipped = 0;
      ChunkBytes& stored = job.stored[c];
      if (H5Dget_chunk_storage_size(datasets[c], offset, &bytes) < 0 || bytes == 0) {
        job.raw = false;
        break;
      }
      stored.reserve(bytes);
      stored.size = bytes;
      if (H5Dread_chunk(datasets[c], H5P_DEFAULT, offset, &skipped, stored.data.get()) < 0 || skipped != 0)
        job.raw = false;
    }
    if (!job.raw) return;  // take_inflated_block reads it through HDF5
    if (!worker) worker = std::make_unique<ChunkWorker>();
    inflating = worker->submit([this] {
      if (!job.inflater) job.inflater = std::make_unique<ChunkInflater>();
      job.values.resize(datasets.size());
      for (std::size_t c = 0; c < datasets.size(); ++c) {
        job.values[c].resize(static_cast<std::size_t>(block_rows));
        if (!job.inflater->inflate(job.stored[c], static_cast<std::size_t>(block_rows), integer[c],
                                   static_cast<std::size_t>(job.size), job.values[c].data()))
          throw std::runtime_error(fmt::format("{} is not a deflated chunk", names[c]));
      }
    });
  }
};

Hdf5TableReader::Hdf5TableReader(std::unique_ptr<State> state) : state_(std::move(state)) {}
Hdf5TableReader::Hdf5TableReader(Hdf5TableReader&&) noexcept = default;
Hdf5TableReader& Hdf5TableReader::operator=(Hdf5TableReader&&) noexcept = default;
Hdf5TableReader::~Hdf5TableReader() = default;

Result<Hdf5TableReader> Hdf5TableReader::open(const std::string& path, const std::string& table,
                                              long block_rows) {
  quiet_hdf5_errors();
  auto state = std::make_unique<State>();
  state->path = path;
  state->table = table;
  state->block_rows = std::max(1L, block_rows);
  state->file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (state->file < 0) return table_read_error(path, "cannot open (not an HDF5 file, or missing)");
  if (H5Lexists(state->file, table.c_str(), H5P_DEFAULT) <= 0)
    return table_read_error(path, fmt::format("no table {} (a different run?)", table));
  const Hdf5Handle group(H5Gopen2(state->file, table.c_str(), H5P_DEFAULT));
  std::vector<std::string> names;
  if (!group.valid() || !column_names(group.get(), names)) return state->error("cannot list its columns");
  if (names.empty()) return state->error("no columns");
  for (const std::string& name : names)
    if (Status added = state->add_column(group.get(), name); !added) return added.error();
  // Blocks of whole chunks when every column is stored as Hdf5File writes them, all chunked alike.
  hsize_t chunk_rows = 0;
  state->chunks_raw = true;
  for (const hid_t dataset : state->datasets) {
    hsize_t rows_here = 0;
    bool integer = false;
    if (!stored_as_written(dataset, rows_here, integer) || (chunk_rows != 0 && rows_here != chunk_rows)) {
      state->chunks_raw = false;
      break;
    }
    chunk_rows = rows_here;
    state->integer.push_back(integer);
  }
  if (state->chunks_raw) state->block_rows = static_cast<long>(chunk_rows);
  state->block.assign(names.size(), std::vector<double>(static_cast<std::size_t>(state->block_rows)));
  return Hdf5TableReader(std::move(state));
}

const std::vector<std::string>& Hdf5TableReader::columns() const {
  return state_->names;
}

const std::vector<std::string>& Hdf5TableReader::units() const {
  return state_->units;
}

long Hdf5TableReader::rows() const {
  return state_->rows;
}

long Hdf5TableReader::rows_read() const {
  return state_->read;
}

Result<bool> Hdf5TableReader::next(std::vector<double>& row) {
  State& s = *state_;
  if (s.read >= s.rows) return false;
  if (s.read >= s.block_start + s.block_size) {
    if (Status read = s.read_block(); !read) return read.error();
  }
  const auto at = static_cast<std::size_t>(s.read - s.block_start);
  row.resize(s.block.size());
  for (std::size_t c = 0; c < s.block.size(); ++c) row[c] = s.block[c][at];
  ++s.read;
  return true;
}

}  // namespace pkm::formats
