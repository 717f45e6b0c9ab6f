#include "plugin_file_checks.hpp"

#include <mechgraph/errors.hpp>

#include <elf.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

namespace mechgraph::detail {
namespace {

// A file opened for reading at offsets, every read checked against the file's size.
class ElfFile {
 public:
  ElfFile(const std::filesystem::path& file, const std::string& where) : where_(where), in_(file, std::ios::binary) {
    if (!in_) throw PluginError(where + ": cannot be opened");
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
    in_.seekg(0);
  }
  std::uint64_t size() const { return size_; }
  bool beyond(std::uint64_t offset, std::uint64_t length) const { return offset > size_ || length > size_ - offset; }
  /// Reads `length` bytes at `offset`; false when they are not all in the file.
  bool read(std::uint64_t offset, void* to, std::uint64_t length) {
    if (beyond(offset, length)) return false;
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(offset));
    return static_cast<bool>(in_.read(static_cast<char*>(to), static_cast<std::streamsize>(length)));
  }
  Elf64_Ehdr header() {
    Elf64_Ehdr h{};
    if (size_ < sizeof h || !read(0, &h, sizeof h) || std::memcmp(h.e_ident, ELFMAG, SELFMAG) != 0)
      throw PluginError(where_ + ": not an ELF shared library (" + std::to_string(size_) + " bytes)");
    return h;
  }

 private:
  std::string where_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

}  // namespace

void check_plugin_ownership(const std::filesystem::path& path, const std::string& where, bool folder) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw PluginError(where + ": cannot be read (" + std::strerror(errno) + ")");
  if (st.st_mode & (S_IWGRP | S_IWOTH))
    throw PluginError(where + ": the " + (folder ? "folder" : "file") +
                      " is writable by group or others, so anyone could plant code in it; refused "
                      "(chmod go-w '" + path.string() + "')");
  if (st.st_uid != ::geteuid() && st.st_uid != 0)
    throw PluginError(where + ": owned by user id " + std::to_string(st.st_uid) + ", neither you nor root; refused");
}

void check_plugin_elf(const std::filesystem::path& file, const std::string& where) {
  ElfFile elf(file, where);
  const Elf64_Ehdr h = elf.header();
  const std::uint64_t size = elf.size();
  if (h.e_ident[EI_CLASS] != ELFCLASS64 || h.e_ident[EI_DATA] != ELFDATA2LSB)
    throw PluginError(where + ": an ELF file for another word size or byte order than this machine's");
#if defined(__x86_64__)
  constexpr unsigned machine = EM_X86_64;
#elif defined(__aarch64__)
  constexpr unsigned machine = EM_AARCH64;
#else
  const unsigned machine = h.e_machine;
#endif
  if (h.e_machine != machine)
    throw PluginError(where + ": built for another processor (ELF machine " + std::to_string(h.e_machine) + ")");
  if (h.e_type != ET_DYN) throw PluginError(where + ": an ELF file but not a shared library");
  if (elf.beyond(h.e_phoff, std::uint64_t{h.e_phnum} * h.e_phentsize) ||
      (h.e_shoff != 0 && elf.beyond(h.e_shoff, std::uint64_t{h.e_shnum} * h.e_shentsize)))
    throw PluginError(where + ": truncated (" + std::to_string(size) + " bytes; its headers reach further)");
  if (h.e_phentsize < sizeof(Elf64_Phdr)) throw PluginError(where + ": its program headers are too small to be ELF64's");
  for (unsigned i = 0; i < h.e_phnum; ++i) {
    Elf64_Phdr ph{};
    if (!elf.read(h.e_phoff + std::uint64_t{i} * h.e_phentsize, &ph, sizeof ph))
      throw PluginError(where + ": truncated program headers");
    if (ph.p_type == PT_LOAD && elf.beyond(ph.p_offset, ph.p_filesz))
      throw PluginError(where + ": truncated (" + std::to_string(size) + " bytes; a segment reaches byte " +
                        std::to_string(ph.p_offset + ph.p_filesz) + ")");
  }
}

std::vector<bool> plugin_exports_symbols(const std::filesystem::path& file, const std::vector<std::string>& names,
                                         const std::string& where) {
  std::vector<bool> found(names.size(), false);
  ElfFile elf(file, where);
  const Elf64_Ehdr h = elf.header();
  if (h.e_shoff == 0 || h.e_shnum == 0 || h.e_shentsize < sizeof(Elf64_Shdr)) return found;
  // The section headers in one read, checked to lie within the file before anything is allocated.
  const std::uint64_t headers_size = std::uint64_t{h.e_shnum} * h.e_shentsize;
  if (elf.beyond(h.e_shoff, headers_size)) throw PluginError(where + ": a section header lies beyond the file");
  std::vector<char> headers(headers_size);
  if (!elf.read(h.e_shoff, headers.data(), headers.size())) throw PluginError(where + ": a section header lies beyond the file");
  auto section = [&](std::uint64_t index) {
    Elf64_Shdr s{};
    if (index >= h.e_shnum) throw PluginError(where + ": a section header lies beyond the file");
    std::memcpy(&s, headers.data() + index * h.e_shentsize, sizeof s);
    return s;
  };
  for (std::uint64_t i = 0; i < h.e_shnum; ++i) {
    const Elf64_Shdr symbols = section(i);
    if (symbols.sh_type != SHT_DYNSYM) continue;
    const Elf64_Shdr strings = section(symbols.sh_link);
    if (symbols.sh_entsize < sizeof(Elf64_Sym) || elf.beyond(symbols.sh_offset, symbols.sh_size) ||
        elf.beyond(strings.sh_offset, strings.sh_size))
      throw PluginError(where + ": its dynamic symbol table lies beyond the file");
    // Both tables are read whole, in two reads (a plugin's are a few hundred KiB); a table beyond
    // any real library's size is refused rather than read.
    constexpr std::uint64_t table_limit = std::uint64_t{256} << 20;
    if (symbols.sh_size > table_limit || strings.sh_size > table_limit)
      throw PluginError(where + ": its dynamic symbol table is larger than 256 MiB; refused");
    std::vector<char> table(symbols.sh_size), text(strings.sh_size);
    if (!elf.read(symbols.sh_offset, table.data(), table.size()) || !elf.read(strings.sh_offset, text.data(), text.size()))
      throw PluginError(where + ": its dynamic symbol table cannot be read");
    const std::uint64_t count = symbols.sh_size / symbols.sh_entsize;
    for (std::uint64_t k = 1; k < count; ++k) {  // entry 0 is the undefined symbol
      Elf64_Sym sym{};
      std::memcpy(&sym, table.data() + k * symbols.sh_entsize, sizeof sym);
      const unsigned binding = ELF64_ST_BIND(sym.st_info);
      if (sym.st_shndx == SHN_UNDEF || (binding != STB_GLOBAL && binding != STB_WEAK)) continue;
      if (sym.st_name >= text.size()) continue;
      for (std::size_t n = 0; n < names.size(); ++n) {
        // The name and its terminating zero, where this symbol's name starts.
        const std::string& name = names[n];
        if (name.size() + 1 <= text.size() - sym.st_name && std::memcmp(text.data() + sym.st_name, name.c_str(), name.size() + 1) == 0)
          found[n] = true;
      }
    }
  }
  return found;
}

}  // namespace mechgraph::detail
