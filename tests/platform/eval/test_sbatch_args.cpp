// SPDX-License-Identifier: MIT
// The extra sbatch arguments: read as sbatch 22.05 reads them (glibc's getopt_long over sbatch's
// option table is the oracle), then held to an allow-list. The family of redirecting forms the
// old deny-list let through: glued short options, abbreviations, values in the next
// word, letters bunched together, the hetjob separator, bare words that become the script.
#include <catch2/catch.hpp>

#include "platform/core/errors.hpp"
#include "platform/eval/executor.hpp"
#include "platform/eval/sbatch_args.hpp"

using namespace smi::eval;

namespace {

std::vector<std::string> words(const std::string& s) {
  ExecutorConfig c;
  c.set("sbatch", s);
  return c.sbatch_args;
}

// Our parse agrees with getopt_long on `s`: both refuse, or both give the same options.
void agrees(const std::vector<std::string>& w) {
  std::vector<std::pair<std::string, std::string>> want;
  const bool ok = smi::eval::sbatch_getopt_reference(w, want);
  INFO("words: " << Catch::Detail::stringify(w));
  if (!ok) {
    CHECK_THROWS_AS(parse_sbatch_args(w), smi::InvalidArgument);
    return;
  }
  std::vector<std::pair<std::string, std::string>> got;
  for (const auto& o : parse_sbatch_args(w)) got.emplace_back(o.name, o.value);
  CHECK(got == want);
}

}  // namespace

TEST_CASE("sbatch arguments resolve as getopt_long resolves them") {
  const std::vector<std::vector<std::string>> cases = {
      {"-o/tmp/x"}, {"-e/tmp/x"}, {"-D/tmp"}, {"-i/etc/passwd"}, {"--outp=/tmp/x"}, {"--err=/tmp/x"},
      {"--chd=/tmp"}, {"--wra=id"}, {"-a0-3"}, {"-Jname"}, {"-Ho/tmp/x"}, {"-o", "/tmp/x"}, {"--output", "/x"},
      {"--gres=gpu:1", "--constraint=avx2"}, {"-N2", "-n", "4"}, {"--exclusive"}, {"--exclusive=user"},
      {"--gr=gpu:1"}, {"--con=x"}, {"--mem-per-cpu=2G"}, {"--mem-per=2G"}, {"--nodes"}, {"-N"}, {"--"}, {"x.sh"},
      {":"}, {"-"}, {"--exp=ALL,BASH_ENV=/tmp/e"}, {"--export-f=/tmp/e"}, {"--no-kill=x"}, {"-kfoo"}, {"--hold=1"},
      {"-Z"}, {"--gres", "--output=/x"}, {"--time=5", "extra"}, {"-vvv"}, {"--bb=x"}, {"--nodefile=/etc/hosts"}};
  for (const auto& w : cases) agrees(w);
}

TEST_CASE("every redirecting or identity-changing form is refused, whatever its spelling") {
  // The ten forms a deny-list let through and their relatives: output, error, input, folder, script text,
  // array, job name, environment, files sbatch reads.
  for (const char* s : {"-o/tmp/x", "-e/tmp/x", "-D/tmp", "-i/tmp/x", "--outp=/tmp/x", "--err=/tmp/x", "--chd=/tmp",
                        "--wra=id", "-a0-3", "-Jname", "-Ho/tmp/x", "-o /tmp/x", "--output /tmp/x", "--ou=/x",
                        "--export=ALL,BASH_ENV=/tmp/e", "--exp=ALL", "--export-file=/tmp/e", "--get-user-env",
                        "--nodefile=/etc/hosts", "-F/etc/hosts", "--bbf=/tmp/b", "--wrap=id", "--uid=0", "--gid=0",
                        "--container=/tmp/c", "--dependency=afterok:1", "--parsable", "--hold", "--test-only",
                        "--open-mode=append", "--propagate=ALL", "--clusters=other", "-Mother", "--wait"}) {
    INFO(s);
    CHECK_THROWS_AS(check_sbatch_args(words(s)), smi::InvalidArgument);
  }
}

TEST_CASE("words sbatch would not read as options are refused, naming them") {
  CHECK_THROWS_WITH(check_sbatch_args({"/tmp/evil.sh"}), Catch::Contains("'/tmp/evil.sh'") && Catch::Contains("script"));
  CHECK_THROWS_WITH(check_sbatch_args({"--gres=gpu:1", "--", "--output=/x"}), Catch::Contains("'--'"));
  CHECK_THROWS_WITH(check_sbatch_args({"--gres=gpu:1", ":", "--output=/x"}), Catch::Contains("':'"));
  CHECK_THROWS_WITH(check_sbatch_args({"--mem-per=2G"}), Catch::Contains("ambiguous") && Catch::Contains("--mem-per-cpu"));
  CHECK_THROWS_WITH(check_sbatch_args({"--gresx=1"}), Catch::Contains("no option '--gresx'"));
  CHECK_THROWS_WITH(check_sbatch_args({"-N"}), Catch::Contains("needs a value"));
  CHECK_THROWS_WITH(check_sbatch_args({"-o/tmp/x"}), Catch::Contains("--output"));
  CHECK_THROWS_WITH(check_sbatch_args({"--outp=/tmp/x"}), Catch::Contains("--output"));
}

TEST_CASE("resource options pass, in any legal spelling") {
  CHECK_NOTHROW(check_sbatch_args(words("--gres=gpu:1 --constraint=avx2 -N2 -n 4 --exclusive --mem-per-cpu=2G")));
  CHECK_NOTHROW(check_sbatch_args(words("--gpus-per-n=1 -Cavx2 --reserv=r1 --ntasks-per-n 2")));
  const auto v = parse_sbatch_args(words("-Cavx2 --gres gpu:1"));
  REQUIRE(v.size() == 2);
  CHECK(v[0].name == "constraint");
  CHECK(v[0].value == "avx2");
  CHECK(v[1].name == "gres");
  CHECK(v[1].value == "gpu:1");
}

TEST_CASE("the executor's validation uses the allow-list") {
  ExecutorConfig c;
  c.set("sbatch=-o/tmp/x");
  CHECK_THROWS_WITH(c.validate(), Catch::Contains("-o/tmp/x") && Catch::Contains("--output"));
  ExecutorConfig d;
  d.set("sbatch=--gres=gpu:1");
  CHECK_NOTHROW(d.validate());
}
