// io/file: bounded reads that refuse what is not a regular file, and
// all-or-nothing writes.

#include "io/file.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <catch2/catch.hpp>
#include <cerrno>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "geometry/core/errors.h"
#include "tests/io/mesh/temp_dir.h"

using namespace fabmesh;
using test::TempDir;
namespace fs = std::filesystem;

namespace {

// The pid of a process that has exited and been reaped.
pid_t dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return pid;
}

}  // namespace

TEST_CASE("read_file: a FIFO, a device and a folder are refused before any byte is read",
          "[io][file][errors]") {
  const TempDir dir;
  const std::string fifo = dir.file("pipe");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // No writer ever opens the FIFO: a blocking read would wait forever.
  CHECK_THROWS_WITH(read_file(fifo, 1000, "design file"), Catch::Contains("pipe") && Catch::Contains("FIFO"));
  CHECK_THROWS_WITH(read_file("/dev/zero", 1000, "design file"), Catch::Contains("character device"));
  CHECK_THROWS_WITH(read_file(dir.file(""), 1000, "design file"), Catch::Contains("folder"));
  CHECK_THROWS_AS(read_file(dir.file("missing"), 1000, "design file"), FileError);
}

TEST_CASE("read_file: a file larger than the limit is refused naming the limit", "[io][file][errors]") {
  const TempDir dir;
  const std::string path = dir.write("big.txt", std::string(1001, 'x'));
  CHECK(read_file(path, 1001, "points file").size() == 1001);
  CHECK_THROWS_WITH(read_file(path, 1000, "points file"),
                    Catch::Contains("points file") && Catch::Contains("1000 bytes"));
}

TEST_CASE("write_files_atomically: a failed rename keeps the previous files and leaves no temporary",
          "[io][file][errors]") {
  const TempDir dir;
  const std::string stl = dir.file("cup.stl"), drc = dir.file("cup.drc"), ply = dir.file("cup.ply");
  write_file_atomically(stl, "previous stl");
  fs::create_directory(drc);  // a folder where the second file should go: its rename fails
  CHECK_THROWS_WITH(write_files_atomically({{stl, "new stl"}, {drc, "new drc"}, {ply, "new ply"}}),
                    Catch::Contains("cup.drc"));
  CHECK(read_file(stl) == "previous stl");
  CHECK_FALSE(fs::exists(ply));
  CHECK(fs::is_directory(drc));
  CHECK(fs::is_empty(drc));
  // Nothing else is left in the folder: no temporary, no backup link.
  std::vector<std::string> names = dir.listing();
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"cup.drc", "cup.stl"});

  // A first output that did not exist before is removed again.
  fs::remove(stl);
  CHECK_THROWS(write_files_atomically({{stl, "new stl"}, {drc, "new drc"}}));
  CHECK_FALSE(fs::exists(stl));
  CHECK(dir.listing() == std::vector<std::string>{"cup.drc"});
}

TEST_CASE("write_file_atomically: stale temporaries of dead processes go, a live process's stay",
          "[io][file]") {
  const TempDir dir;
  const std::string path = dir.file("cup.stl");
  const std::string stale = temporary_prefix(path) + std::to_string(dead_pid()) + "-0badf00d";
  // The parent of this test process is alive (and not this process).
  const std::string live = temporary_prefix(path) + std::to_string(::getppid()) + "-0badf00d";
  const std::string other = dir.file(".cup.stl.tmp-otherhost-1-0badf00d");  // another host: not ours to judge
  for (const std::string& p : {stale, live, other}) write_file_atomically(p, "partial");
  write_file_atomically(path, "whole");
  CHECK(read_file(path) == "whole");
  CHECK_FALSE(fs::exists(stale));
  CHECK(fs::exists(live));
  CHECK(fs::exists(other));
}

TEST_CASE("write_file_atomically: a temporary of this PID left by an earlier process is stale",
          "[io][file]") {
  // The same PID with another start time (or none: fabmesh before 0.3), and a
  // running process whose PID was reused since (its start time differs).
  const TempDir dir;
  const std::string path = dir.file("cup.stl");
  const std::string earlier = temporary_prefix(path) + std::to_string(::getpid()) + "-s1-0badf00d";
  const std::string untokened = temporary_prefix(path) + std::to_string(::getpid()) + "-0badf00d";
  const std::string reused = temporary_prefix(path) + std::to_string(::getppid()) + "-s1-0badf00d";
  for (const std::string& p : {earlier, untokened, reused})
    dir.write(fs::path(p).filename().string(), "partial");
  write_file_atomically(path, "whole");
  CHECK(dir.listing() == std::vector<std::string>{"cup.stl"});
}

TEST_CASE("PendingFile: another writer of the same path in this process keeps its temporary", "[io][file]") {
  // Issue 43: a second writer took the first one's temporary for a killed
  // run's (same PID) and removed it; the first then could not be renamed.
  const TempDir dir;
  const std::string path = dir.file("cup.stl");
  PendingFile first(path);
  first.write("first");
  write_file_atomically(path, "second");
  CHECK(read_file(path) == "second");
  commit_file(std::move(first));
  CHECK(read_file(path) == "first");
  CHECK(dir.listing() == std::vector<std::string>{"cup.stl"});
}

TEST_CASE("write_file_atomically: twelve threads writing one path all succeed, one whole version stays",
          "[io][file][threads]") {
  const TempDir dir;
  const std::string path = dir.file("export.glb");
  constexpr int kThreads = 12, kWrites = 25;
  std::atomic<int> failures{0};
  std::vector<std::string> messages(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < kWrites; ++i) {
        try {
          // Single files and sets of two, as exports and jobs write them.
          const std::string bytes = std::string(4096 * (t + 1), static_cast<char>('a' + t));
          if (i % 2 == 0) {
            write_file_atomically(path, bytes);
          } else {
            write_files_atomically({{path, bytes}, {path + ".json", bytes}});
          }
        } catch (const std::exception& e) {
          ++failures;
          messages[static_cast<std::size_t>(t)] = e.what();
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  for (const std::string& m : messages) CHECK(m.empty());
  CHECK(failures == 0);
  const std::string last = read_file(path);
  REQUIRE_FALSE(last.empty());
  CHECK(last == std::string(last.size(), last[0]));  // one writer's whole bytes
  CHECK(last.size() == 4096 * static_cast<std::size_t>(last[0] - 'a' + 1));
  std::vector<std::string> names = dir.listing();
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"export.glb", "export.glb.json"});
}

TEST_CASE("commit_files: a rename that fails is the machine's failure, not bad input", "[io][file][errors]") {
  // The temporary removed under the writer (by another program): ENOENT.
  const TempDir dir;
  const std::string path = dir.file("cup.stl");
  PendingFile file(path);
  file.write("bytes");
  for (const std::string& name : dir.listing()) fs::remove(dir.file(name));
  try {
    commit_file(std::move(file));
    FAIL("the commit did not fail");
  } catch (const MachineError& e) {
    CHECK(e.error_number() == ENOENT);
    CHECK_THAT(e.what(), Catch::Contains("cup.stl: cannot rename the temporary file into place"));
  }
  CHECK(dir.listing().empty());
}

TEST_CASE("write_file_atomically: the file gets the process's umask", "[io][file]") {
  const TempDir dir;
  const mode_t previous = ::umask(027);
  write_file_atomically(dir.file("a.stl"), "x");
  ::umask(077);
  write_file_atomically(dir.file("b.stl"), "x");
  ::umask(previous);
  struct stat a {
  }, b{};
  REQUIRE(::stat(dir.file("a.stl").c_str(), &a) == 0);
  REQUIRE(::stat(dir.file("b.stl").c_str(), &b) == 0);
  CHECK((a.st_mode & 0777) == 0640);
  CHECK((b.st_mode & 0777) == 0600);
}

TEST_CASE("PendingFile: a line at a time and in blocks, committed alone with commit_file", "[io][file]") {
  const TempDir dir;
  const std::string target = dir.file("summary.csv");
  std::string expected;
  {
    PendingFile file(target);
    for (int i = 0; i < 200000; ++i) {  // 2.3 MB of small pieces: gathered, written a block at a time
      const std::string line = std::to_string(i) + ",ok\n";
      file.write(line);
      expected += line;
    }
    const std::string block(3 << 20, 'x');  // larger than a block: written through
    file.write(block);
    expected += block;
    file.write("end\n");
    expected += "end\n";
    PendingFile moved(std::move(file));            // what is gathered moves along
    CHECK_FALSE(std::filesystem::exists(target));  // nothing under the name before the commit
    commit_file(std::move(moved));
  }
  CHECK(read_file(target) == expected);
  CHECK(dir.listing() == std::vector<std::string>{"summary.csv"});
}

TEST_CASE("PendingFile: bytes written in pieces reach the target only when committed, and never partly",
          "[io][file]") {
  const TempDir dir;
  const std::string target = dir.file("cup.stl");
  write_file_atomically(target, "previous");
  {
    PendingFile abandoned(target);  // e.g. an encoder failed half-way
    abandoned.write("half of a new ");
  }
  CHECK(read_file(target) == "previous");
  CHECK(dir.listing() == std::vector<std::string>{"cup.stl"});
  {
    std::vector<PendingFile> unfinished;
    unfinished.emplace_back(target);
    unfinished.back().write("not flushed");
    CHECK_THROWS_WITH(commit_files(unfinished), Catch::Contains("before it was finished"));
  }
  CHECK(read_file(target) == "previous");
  CHECK(dir.listing() == std::vector<std::string>{"cup.stl"});
  std::vector<PendingFile> files;
  files.emplace_back(target);
  files.emplace_back(dir.file("cup.drc"));
  for (const std::string_view piece : {"new ", "bytes ", "in pieces"}) files[0].write(piece);
  files[1].write("drc");
  for (PendingFile& f : files) f.finish();
  CHECK_THROWS(files[0].write("after finish"));
  commit_files(files);
  files.clear();
  CHECK(read_file(target) == "new bytes in pieces");
  CHECK(read_file(dir.file("cup.drc")) == "drc");
  std::vector<std::string> names = dir.listing();
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"cup.drc", "cup.stl"});
}
