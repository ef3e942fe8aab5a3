// A libFuzzer-compatible driver for compilers without libFuzzer (GCC, which Debian's ITK 5.2 requires):
// loads a seed corpus and feeds LLVMFuzzerTestOneInput with seeded random mutations (bit flips, byte
// overwrites, truncation, insertion, chunk copies) until -max_total_time seconds have passed. Not
// coverage-guided, so weaker than libFuzzer; run under ASan+UBSan it still finds crashes and leaks.
//
// usage: fuzz_X_mutate [-max_total_time=SECONDS] [-timeout=SECONDS] [-seed=N] CORPUS_DIR_OR_FILE...
// An input that takes longer than -timeout (default 10 s) is a hang: it is saved as timeout-input.bin and
// the driver exits with code 70, as libFuzzer's -timeout does.
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

const std::vector<std::uint8_t>* g_current = nullptr;

extern "C" void on_timeout(int) {
  if (g_current) {
    std::FILE* f = std::fopen("timeout-input.bin", "wb");
    if (f) {
      std::fwrite(g_current->data(), 1, g_current->size(), f);
      std::fclose(f);
    }
  }
  const char msg[] = "mutation driver: an input ran past -timeout (a hang); saved as timeout-input.bin\n";
  (void)!write(2, msg, sizeof(msg) - 1);
  _exit(70);
}

std::vector<std::uint8_t> read_all(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void mutate(std::vector<std::uint8_t>& d, std::mt19937_64& rng) {
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t n = d.size();
    switch (rng() % 6) {
      case 0:  // flip a bit
        if (n) d[rng() % n] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
        break;
      case 1:  // overwrite a byte with an interesting value
        if (n) {
          static const std::uint8_t interesting[] = {0, 1, 0x7f, 0x80, 0xff, '0', '9', '-', '.', 'e', '\n', ' '};
          d[rng() % n] = interesting[rng() % sizeof(interesting)];
        }
        break;
      case 2:  // truncate
        if (n) d.resize(rng() % n);
        break;
      case 3:  // insert random bytes
        if (n < (1u << 20)) {
          const std::size_t at = n ? rng() % n : 0, len = 1 + rng() % 8;
          for (std::size_t k = 0; k < len; ++k)
            d.insert(d.begin() + static_cast<std::ptrdiff_t>(at), static_cast<std::uint8_t>(rng()));
        }
        break;
      case 4:  // copy a chunk elsewhere
        if (n > 2) {
          const std::size_t from = rng() % n, len = 1 + rng() % std::min<std::size_t>(64, n - from), to = rng() % n;
          std::vector<std::uint8_t> chunk(d.begin() + static_cast<std::ptrdiff_t>(from),
                                          d.begin() + static_cast<std::ptrdiff_t>(from + len));
          d.insert(d.begin() + static_cast<std::ptrdiff_t>(to), chunk.begin(), chunk.end());
        }
        break;
      default:  // overwrite 4 bytes with a random integer (sizes, dims, offsets)
        if (n >= 4) {
          const std::uint32_t v = static_cast<std::uint32_t>(rng());
          std::memcpy(&d[rng() % (n - 3)], &v, 4);
        }
        break;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 60;
  unsigned timeout = 10;
  std::uint64_t seed = 1;
  std::vector<std::vector<std::uint8_t>> corpus;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("-max_total_time=", 0) == 0) {
      seconds = std::stod(a.substr(16));
    } else if (a.rfind("-timeout=", 0) == 0) {
      timeout = static_cast<unsigned>(std::stoul(a.substr(9)));
    } else if (a.rfind("-seed=", 0) == 0) {
      seed = std::stoull(a.substr(6));
    } else if (std::filesystem::is_directory(a)) {
      for (const auto& e : std::filesystem::recursive_directory_iterator(a))
        if (e.is_regular_file()) corpus.push_back(read_all(e.path()));
    } else if (std::filesystem::is_regular_file(a)) {
      corpus.push_back(read_all(a));
    }
  }
  if (corpus.empty()) corpus.push_back({});
  std::signal(SIGALRM, on_timeout);
  for (const auto& c : corpus) {
    g_current = &c;
    alarm(timeout);
    LLVMFuzzerTestOneInput(c.data(), c.size());
  }
  std::mt19937_64 rng(seed);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  std::size_t runs = 0;
  while (std::chrono::steady_clock::now() < end) {
    std::vector<std::uint8_t> d = corpus[rng() % corpus.size()];
    mutate(d, rng);
    g_current = &d;
    alarm(timeout);
    LLVMFuzzerTestOneInput(d.data(), d.size());
    alarm(0);
    ++runs;
  }
  std::printf("mutation driver: %zu runs in %.0f s over %zu seeds, no crash\n", runs, seconds, corpus.size());
  return 0;
}
