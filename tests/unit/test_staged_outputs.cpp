// Output files (core/staged_outputs.hpp): a run's outputs appear all or none,
// never over one of its inputs, never twice, never through a planted link, and
// keep the permissions of the files they replace.

#include "core/staged_outputs.hpp"
#include "scratch_dir.hpp"
#include "voronoimesh/core/errors.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace vm {
namespace {

namespace fs = std::filesystem;
using detail::StagedOutputs;
using StagedOutputsTest = test::ScratchDir;

void say(std::ostream& out, const char* text) { out << text; }

size_t files_in(const fs::path& dir) {
  size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += (void(e), 1);
  return n;
}

TEST_F(StagedOutputsTest, files_appear_together_at_commit_and_not_without_it) {
  {
    StagedOutputs staged;
    staged.write(path("a.txt"), [](std::ostream& o) { say(o, "a"); });
    staged.write(path("b.txt"), [](std::ostream& o) { say(o, "b"); });
    EXPECT_FALSE(fs::exists(path("a.txt")));
    EXPECT_FALSE(fs::exists(path("b.txt")));
  } // a failure later in the run: nothing was committed
  EXPECT_EQ(files_in(dir_), 0u) << "temporaries or outputs were left behind";
  StagedOutputs staged;
  staged.write(path("a.txt"), [](std::ostream& o) { say(o, "a"); });
  staged.write(path("b.txt"), [](std::ostream& o) { say(o, "b"); });
  staged.commit();
  EXPECT_EQ(read_bytes(path("a.txt")), "a");
  EXPECT_EQ(read_bytes(path("b.txt")), "b");
  EXPECT_EQ(files_in(dir_), 2u);
}

TEST_F(StagedOutputsTest, a_body_that_throws_leaves_no_temporary) {
  StagedOutputs staged;
  EXPECT_THROW(staged.write(path("a.txt"), [](std::ostream&) { throw std::runtime_error("disk on fire"); }),
               std::runtime_error);
  EXPECT_EQ(files_in(dir_), 0u);
}

TEST_F(StagedOutputsTest, an_input_is_never_an_output_even_through_a_link) {
  std::ofstream(path("scene.json")) << "{}";
  fs::create_symlink(path("scene.json"), path("link.json"));
  StagedOutputs staged({path("scene.json")});
  EXPECT_THROW(staged.write(path("scene.json"), [](std::ostream& o) { say(o, "x"); }), InvalidInput);
  EXPECT_THROW(staged.write(path("link.json"), [](std::ostream& o) { say(o, "x"); }), InvalidInput);
  EXPECT_EQ(read_bytes(path("scene.json")), "{}");
}

TEST_F(StagedOutputsTest, one_file_is_written_once) {
  StagedOutputs staged;
  staged.write(path("a.txt"), [](std::ostream& o) { say(o, "a"); });
  EXPECT_THROW(staged.write(path("./a.txt"), [](std::ostream& o) { say(o, "b"); }), InvalidInput);
}

TEST_F(StagedOutputsTest, a_planted_link_at_the_temporary_name_is_never_followed) {
  std::ofstream(path("victim.txt")) << "keep me";
  const std::string pid = std::to_string(::getpid());
  fs::create_symlink(path("victim.txt"), path("out.ply.tmp-" + pid));
  for (int k = 0; k < 20; ++k)
    fs::create_symlink(path("victim.txt"), path("out.ply.tmp-" + pid + "-" + std::to_string(k)));
  StagedOutputs staged;
  staged.write(path("out.ply"), [](std::ostream& o) { say(o, "mesh"); });
  staged.commit();
  EXPECT_EQ(read_bytes(path("victim.txt")), "keep me");
  EXPECT_FALSE(fs::is_symlink(path("out.ply")));
  EXPECT_EQ(read_bytes(path("out.ply")), "mesh");
}

TEST_F(StagedOutputsTest, a_replaced_file_keeps_its_permissions) {
  std::ofstream(path("private.ply")) << "old";
  ::chmod(path("private.ply").c_str(), 0600);
  detail::write_atomically(path("private.ply"), [](std::ostream& o) { say(o, "new"); });
  struct stat st {};
  ASSERT_EQ(::stat(path("private.ply").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  EXPECT_EQ(read_bytes(path("private.ply")), "new");
}

TEST_F(StagedOutputsTest, a_new_file_gets_what_the_umask_leaves) {
  const mode_t mask = ::umask(027);
  detail::write_atomically(path("new.ply"), [](std::ostream& o) { say(o, "new"); });
  ::umask(mask);
  struct stat st {};
  ASSERT_EQ(::stat(path("new.ply").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
}

} // namespace
} // namespace vm
