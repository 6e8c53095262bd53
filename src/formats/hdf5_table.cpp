#include "formats/hdf5_table.hpp"

#include <fmt/format.h>
#include <hdf5.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <deque>
#include <future>
#include <memory>

#include "formats/chunk_worker.hpp"
#include "formats/hdf5_chunk_filter.hpp"
#include "formats/hdf5_handle.hpp"

namespace pkm::formats {

namespace {

Error hdf5_error(const std::string& path, const std::string& what) {
  Error e = make_error(ErrorCode::io, fmt::format("cannot write {}: {}", path, what));
  e.location.file = path;
  return e;
}

using Handle = Hdf5Handle;

/// Deflate level 1: most of the size gain of the higher levels at a fraction of their time.
constexpr int kDeflate = 1;

// A variable-length UTF-8 string attribute (h5py reads it as str).
bool write_string_attribute(hid_t owner, const std::string& name, const std::string& value) {
  const Handle type(H5Tcopy(H5T_C_S1));
  if (!type.valid() || H5Tset_size(type.get(), H5T_VARIABLE) < 0 ||
      H5Tset_cset(type.get(), H5T_CSET_UTF8) < 0)
    return false;
  const Handle space(H5Screate(H5S_SCALAR));
  const Handle attribute(H5Acreate2(owner, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT));
  const char* text = value.c_str();
  return attribute.valid() && H5Awrite(attribute.get(), type.get(), &text) >= 0;
}

// A growing, chunked, shuffled and deflated 1-D dataset.
hid_t create_column(hid_t group, const Hdf5Column& column, hsize_t chunk_rows) {
  const hsize_t dims[1] = {0}, max_dims[1] = {H5S_UNLIMITED}, chunk[1] = {chunk_rows};
  const Handle space(H5Screate_simple(1, dims, max_dims));
  const Handle properties(H5Pcreate(H5P_DATASET_CREATE));
  if (H5Pset_chunk(properties.get(), 1, chunk) < 0 || H5Pset_shuffle(properties.get()) < 0 ||
      H5Pset_deflate(properties.get(), kDeflate) < 0)
    return -1;
  const hid_t type = column.integer ? H5T_STD_I64LE : H5T_IEEE_F64LE;
  const hid_t dataset =
      H5Dcreate2(group, column.name.c_str(), type, space.get(), H5P_DEFAULT, properties.get(), H5P_DEFAULT);
  if (dataset < 0) return -1;
  if (!write_string_attribute(dataset, "unit", column.unit)) {
    H5Dclose(dataset);
    return -1;
  }
  return dataset;
}

}  // namespace

int quantum_bits_for_decimals(int decimals) {
  return static_cast<int>(std::ceil(decimals * std::log2(10.0)));
}

int significant_bits_for_digits(int digits) {
  return static_cast<int>(std::ceil(digits * std::log2(10.0))) + 1;
}

double round_to_significant_bits(double value, int bits) {
  if (!std::isfinite(value) || value == 0.0 || bits >= 53) return value;
  constexpr int kFractionBits = 52;
  auto word = std::bit_cast<std::uint64_t>(value);
  if ((word >> kFractionBits & 0x7FF) != 0 && bits > 0) {
    // A normal number: its 53 significant bits are the implicit 1 and the fraction field, so rounding to
    // `bits` of them is rounding the word's low 53 − bits bits, half to even (as nearbyint); a carry out of
    // the fraction raises the exponent, which is the right result (…111 rounds up to the next power of two).
    const int dropped = kFractionBits + 1 - bits;
    const std::uint64_t unit = std::uint64_t{1} << dropped;
    // The last kept bit: in the fraction field, or the implicit 1 itself when only one bit is kept.
    const std::uint64_t last_kept = bits == 1 ? 1 : (word >> dropped & 1);
    word += (unit >> 1) - 1 + last_kept;
    return std::bit_cast<double>(word & ~(unit - 1));
  }
  // Subnormal: the definition itself.
  int exponent = 0;
  const double mantissa =
      std::frexp(value, &exponent);  // value = mantissa · 2^exponent, 0.5 ≤ |mantissa| < 1
  return std::ldexp(std::nearbyint(std::ldexp(mantissa, bits)), exponent - bits);
}

namespace {

/// A column's values rounded to its quantum (`scale` = 2^quantum_bits) or to its significant bits, in place:
/// v·2^k rounded and scaled back are exact operations on doubles.
void round_column(const Hdf5Column& column, double scale, double* values, std::size_t count) {
  if (scale > 0.0) {
    for (std::size_t i = 0; i < count; ++i) values[i] = std::nearbyint(values[i] * scale) / scale;
  } else if (column.significant_bits > 0) {
    for (std::size_t i = 0; i < count; ++i)
      values[i] = round_to_significant_bits(values[i], column.significant_bits);
  }
}

}  // namespace

/// A full chunk of every column, shuffled and deflated on the table's filter thread (hdf5_chunk_filter.hpp).
/// A few per table, used again in turn: their buffers keep their storage, so a long run allocates (and
/// clears) nothing per chunk.
struct ChunkJob {
  long first_row = 0;
  std::vector<std::vector<double>> values;  ///< a column each
  std::vector<ChunkBytes> deflated;         ///< a column each
  std::vector<std::int64_t> integers;       ///< an integer column's values, converted

  /// On the filter thread, with its deflater (made there on first use): the values rounded as their
  /// columns say, then shuffled and deflated.
  void deflate(const std::vector<Hdf5Column>& columns, const std::vector<double>& scale,
               std::unique_ptr<ChunkDeflater>& deflater) {
    static_assert(std::endian::native == std::endian::little, "the chunks are stored little-endian as is");
    if (!deflater) deflater = std::make_unique<ChunkDeflater>(kDeflate);
    deflated.resize(columns.size());
    for (std::size_t c = 0; c < columns.size(); ++c) {
      std::vector<double>& column = values[c];
      round_column(columns[c], scale[c], column.data(), column.size());
      if (columns[c].integer) {
        integers.assign(column.begin(), column.end());
        deflater->shuffle_deflate(integers.data(), integers.size(), sizeof(std::int64_t), deflated[c]);
      } else {
        deflater->shuffle_deflate(column.data(), column.size(), sizeof(double), deflated[c]);
      }
    }
  }
};

struct Hdf5Table::State {
  std::string path, name;
  std::vector<Hdf5Column> columns;
  std::vector<hid_t> datasets;
  std::vector<double> scale;                  // 2^quantum_bits, or 0: kept exactly
  std::vector<std::vector<double>> buffered;  // a chunk per column
  std::vector<std::int64_t> integers;         // an integer column's chunk, converted when written
  long chunk_rows = 0, written = 0, pending = 0;
  /// Full chunks being filtered while the next one fills: the run's writing costs its ticks the time of
  /// copying their values, and the deflating goes to the other core. A few may wait, so that the thread
  /// filling them does not stop whenever the filter thread is not the one running (two cores, more threads).
  static constexpr std::size_t kChunksInFlight = 3;
  std::array<ChunkJob, kChunksInFlight> jobs;  ///< a ring: the oldest being filtered at `oldest`
  std::deque<std::future<void>> filtering;     ///< the jobs in flight, oldest first
  std::size_t oldest = 0;
  std::unique_ptr<ChunkDeflater> deflater;     ///< used on the filter thread only
  std::unique_ptr<ChunkWorker> filter_thread;  ///< one for the table's whole life (chunk_worker.hpp)

  ~State() {
    for (std::future<void>& f : filtering) f.wait();
    for (const hid_t d : datasets)
      if (H5Iis_valid(d) > 0) H5Dclose(d);
  }

  /// Hands the full chunk to the filter thread, after writing the oldest one in flight when all are.
  Status filter_full_chunk() {
    if (filtering.size() == kChunksInFlight)
      if (Status stored = store_oldest(); !stored) return stored;
    ChunkJob& job = jobs[(oldest + filtering.size()) % kChunksInFlight];
    if (job.values.empty()) job.values.assign(columns.size(), std::vector<double>(chunk_rows));
    job.values.swap(buffered);
    job.first_row = written;
    if (!filter_thread) filter_thread = std::make_unique<ChunkWorker>();
    filtering.push_back(filter_thread->submit([this, &job] { job.deflate(columns, scale, deflater); }));
    written += pending;
    pending = 0;
    return ok_status();
  }

  /// Writes the oldest chunk in flight as HDF5 would have stored it (H5Dwrite_chunk, all filters applied).
  Status store_oldest() {
    std::future<void> done = std::move(filtering.front());
    filtering.pop_front();
    ChunkJob& job = jobs[oldest];
    oldest = (oldest + 1) % kChunksInFlight;
    try {
      done.get();
    } catch (const std::exception& e) {
      return hdf5_error(path, fmt::format("cannot compress {}: {}", name, e.what()));
    }
    const hsize_t offset[1] = {static_cast<hsize_t>(job.first_row)};
    const hsize_t size[1] = {static_cast<hsize_t>(job.first_row + chunk_rows)};
    for (std::size_t c = 0; c < datasets.size(); ++c) {
      const ChunkBytes& bytes = job.deflated[c];
      if (H5Dset_extent(datasets[c], size) < 0 ||
          H5Dwrite_chunk(datasets[c], H5P_DEFAULT, 0, offset, bytes.size, bytes.data.get()) < 0)
        return hdf5_error(path, fmt::format("cannot write {}/{}", name, columns[c].name));
    }
    return ok_status();
  }

  /// Writes every chunk in flight.
  Status store_filtered() {
    while (!filtering.empty())
      if (Status stored = store_oldest(); !stored) return stored;
    return ok_status();
  }

  /// The rows of a chunk that is not full (the end of the table), through HDF5's own filters.
  Status write_pending() {
    if (Status stored = store_filtered(); !stored) return stored;
    if (pending == 0) return ok_status();
    const hsize_t start[1] = {static_cast<hsize_t>(written)}, count[1] = {static_cast<hsize_t>(pending)};
    const hsize_t size[1] = {static_cast<hsize_t>(written + pending)};
    for (std::size_t c = 0; c < datasets.size(); ++c) {
      round_column(columns[c], scale[c], buffered[c].data(), static_cast<std::size_t>(pending));
      if (H5Dset_extent(datasets[c], size) < 0)
        return hdf5_error(path, fmt::format("cannot extend {}/{}", name, columns[c].name));
      const Handle file_space(H5Dget_space(datasets[c]));
      const Handle memory_space(H5Screate_simple(1, count, nullptr));
      if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) < 0)
        return hdf5_error(path, fmt::format("cannot select rows of {}/{}", name, columns[c].name));
      herr_t status;
      if (columns[c].integer) {
        for (long r = 0; r < pending; ++r) integers[r] = static_cast<std::int64_t>(buffered[c][r]);
        status = H5Dwrite(datasets[c], H5T_NATIVE_INT64, memory_space.get(), file_space.get(), H5P_DEFAULT,
                          integers.data());
      } else {
        status = H5Dwrite(datasets[c], H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT,
                          buffered[c].data());
      }
      if (status < 0) return hdf5_error(path, fmt::format("cannot write {}/{}", name, columns[c].name));
    }
    written += pending;
    pending = 0;
    return ok_status();
  }
};

Hdf5Table::Hdf5Table() = default;
Hdf5Table::~Hdf5Table() = default;
Hdf5Table::Hdf5Table(Hdf5Table&&) noexcept = default;
Hdf5Table& Hdf5Table::operator=(Hdf5Table&&) noexcept = default;

Status Hdf5Table::append(const double* values) {
  State& s = *state_;
  // Rounded where the chunk is filtered (round_column), off this thread.
  for (std::size_t c = 0; c < s.columns.size(); ++c) s.buffered[c][s.pending] = values[c];
  if (++s.pending == s.chunk_rows) return s.filter_full_chunk();
  return ok_status();
}

Status Hdf5Table::finish() {
  return state_->write_pending();
}

long Hdf5Table::rows() const {
  return state_->written + state_->pending;
}

Result<Hdf5File> Hdf5File::create(const std::string& path) {
  quiet_hdf5_errors();
  // Closing the file closes its tables' datasets too (a table destroyed later finds them closed).
  const Handle access(H5Pcreate(H5P_FILE_ACCESS));
  if (!access.valid() || H5Pset_fclose_degree(access.get(), H5F_CLOSE_STRONG) < 0)
    return hdf5_error(path, "HDF5 could not set up the file");
  // The metadata cache (the chunk index of every column) grows by default up to 32 MB as the file does: a
  // run's memory would grow with its length. Fixed at 2 MB; the columns are written in order, so little of
  // the index is ever touched again. HDF5 keeps freed blocks in free lists of its own, unbounded by default:
  // bounded too.
  H5set_free_list_limits(1 << 20, 1 << 18, 1 << 20, 1 << 18, 1 << 20, 1 << 18);
  H5AC_cache_config_t cache{};
  cache.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  if (H5Pget_mdc_config(access.get(), &cache) < 0) return hdf5_error(path, "HDF5 could not set up the file");
  cache.set_initial_size = true;
  cache.initial_size = cache.min_size = cache.max_size = std::size_t{2} << 20;
  cache.incr_mode = H5C_incr__off;
  cache.flash_incr_mode = H5C_flash_incr__off;
  cache.decr_mode = H5C_decr__off;
  if (H5Pset_mdc_config(access.get(), &cache) < 0) return hdf5_error(path, "HDF5 could not set up the file");
  // The 1.10 format indexes a column's chunks with an extensible array, not a B-tree that grows in memory.
  if (H5Pset_libver_bounds(access.get(), H5F_LIBVER_V110, H5F_LIBVER_LATEST) < 0)
    return hdf5_error(path, "HDF5 could not set up the file");
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get());
  if (id < 0) return hdf5_error(path, "HDF5 could not create the file");
  return Hdf5File(path, id);
}

Hdf5File::Hdf5File(Hdf5File&& other) noexcept : path_(std::move(other.path_)), id_(other.id_) {
  other.id_ = -1;
}

Hdf5File& Hdf5File::operator=(Hdf5File&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0) H5Fclose(id_);
    path_ = std::move(other.path_);
    id_ = other.id_;
    other.id_ = -1;
  }
  return *this;
}

Hdf5File::~Hdf5File() {
  if (id_ >= 0) H5Fclose(id_);
}

Result<Hdf5Table> Hdf5File::table(const std::string& name, const std::vector<Hdf5Column>& columns,
                                  long chunk_rows) {
  // The columns' order is kept (link creation order), so that a reader sees them as the CSV header has them.
  const Handle group_properties(H5Pcreate(H5P_GROUP_CREATE));
  if (!group_properties.valid() ||
      H5Pset_link_creation_order(group_properties.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0)
    return hdf5_error(path_, fmt::format("cannot set up the table {}", name));
  const Handle group(H5Gcreate2(id_, name.c_str(), H5P_DEFAULT, group_properties.get(), H5P_DEFAULT));
  if (!group.valid()) return hdf5_error(path_, fmt::format("cannot create the table {}", name));
  Hdf5Table table;
  table.state_ = std::make_unique<Hdf5Table::State>();
  Hdf5Table::State& s = *table.state_;
  s.path = path_;
  s.name = name;
  s.columns = columns;
  s.chunk_rows = chunk_rows;
  s.integers.resize(chunk_rows);
  for (const Hdf5Column& column : columns) {
    const hid_t dataset = create_column(group.get(), column, static_cast<hsize_t>(chunk_rows));
    if (dataset < 0)
      return hdf5_error(path_, fmt::format("cannot create the column {}/{}", name, column.name));
    s.datasets.push_back(dataset);
    s.scale.push_back(column.quantum_bits > 0 ? std::ldexp(1.0, column.quantum_bits) : 0.0);
    s.buffered.emplace_back(chunk_rows);
  }
  return table;
}

Status Hdf5File::set_attribute(const std::string& name, const std::string& value) {
  if (!write_string_attribute(id_, name, value))
    return hdf5_error(path_, fmt::format("cannot set the attribute {}", name));
  return ok_status();
}

Status Hdf5File::close() {
  const hid_t id = id_;
  id_ = -1;
  if (id >= 0 && H5Fclose(id) < 0) return hdf5_error(path_, "HDF5 could not close the file");
  return ok_status();
}

namespace {

Error read_error(const std::string& path, const std::string& what) {
  Error e = make_error(ErrorCode::io, fmt::format("cannot read {}: {}", path, what));
  e.location.file = path;
  return e;
}

}  // namespace

Result<Hdf5ColumnData> read_hdf5_column(const std::string& path, const std::string& table,
                                        const std::string& column) {
  quiet_hdf5_errors();
  const Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!file.valid()) return read_error(path, "not an HDF5 file, or missing");
  const std::string name = table + "/" + column;
  const Handle dataset(H5Dopen2(file.get(), name.c_str(), H5P_DEFAULT));
  if (!dataset.valid()) return read_error(path, fmt::format("no column {}", name));
  const Handle space(H5Dget_space(dataset.get()));
  if (H5Sget_simple_extent_ndims(space.get()) != 1)
    return read_error(path, fmt::format("{} is not a column", name));
  hsize_t rows = 0;
  H5Sget_simple_extent_dims(space.get(), &rows, nullptr);
  Hdf5ColumnData data;
  data.values.resize(rows);
  if (rows > 0 &&
      H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.values.data()) < 0)
    return read_error(path, fmt::format("cannot read {}", name));
  if (!read_hdf5_string_attribute(dataset.get(), "unit", data.unit))
    return read_error(path, fmt::format("{} has no unit", name));
  return data;
}

}  // namespace pkm::formats
