// SPDX-License-Identifier: MIT
// The Slurm executor's pure parts on recorded output of Slurm 22.05 (Debian 12): squeue/sacct/
// scontrol parsing, state classes, --time arithmetic, the sbatch line, option checking, and the
// command runner's time limit. The executor against a real cluster: tests/slurm (label slurm).
#include <catch2/catch.hpp>
#include <filesystem>
#include <unistd.h>

#include "platform/eval/executor.hpp"
#include "platform/eval/pending.hpp"
#include "platform/eval/process.hpp"
#include "platform/eval/slurm_cli.hpp"
#include "platform/eval/slurm_executor.hpp"
#include "platform/eval/store.hpp"

using namespace smi::eval;

TEST_CASE("squeue -r -t all lines become one entry per array task") {
  // Recorded: squeue -h -r -t all -o '%i|%T|%r|%A' with a running, a pending, a finished task
  // and a plain job; the unsplit "[5-9%2]" form (no -r) is skipped.
  const std::string out =
      "11_0|COMPLETED|None|12\n11_1|RUNNING|None|13\n11_7|PENDING|JobArrayTaskLimit|11\n42|NODE_FAIL|None|42\n"
      "50_[5-9%2]|PENDING|JobArrayTaskLimit|50\ngarbage line\n\n";
  const auto v = parse_squeue(out);
  REQUIRE(v.size() == 4);
  CHECK(v[0].array_job_id == "11");
  CHECK(v[0].index == 0);
  CHECK(v[0].state == TaskState::Completed);
  CHECK(v[0].raw_id == "12");
  CHECK(v[1].state == TaskState::Running);
  CHECK(v[2].index == 7);
  CHECK(v[2].state == TaskState::Pending);
  CHECK(v[2].reason == "JobArrayTaskLimit");
  CHECK(v[3].array_job_id == "42");
  CHECK(v[3].index == -1);
  CHECK(v[3].state == TaskState::NodeFail);
}

TEST_CASE("states: infrastructure failures are requeued, the run's own failures are final") {
  for (const char* s : {"NODE_FAIL", "PREEMPTED", "BOOT_FAIL"}) {
    CHECK(is_infrastructure(parse_task_state(s)));
    CHECK(is_final(parse_task_state(s)));
  }
  for (const char* s : {"FAILED", "TIMEOUT", "OUT_OF_MEMORY", "CANCELLED", "CANCELLED+", "CANCELLED by 0"}) {
    CHECK_FALSE(is_infrastructure(parse_task_state(s)));
    CHECK(is_final(parse_task_state(s)));
  }
  CHECK(parse_task_state("CANCELLED by 0") == TaskState::Cancelled);
  for (const char* s : {"PENDING", "RUNNING", "COMPLETING", "REQUEUED", "CONFIGURING", "SUSPENDED", "what"})
    CHECK_FALSE(is_final(parse_task_state(s)));
}

TEST_CASE("sacct -P output, steps left out; sbatch --parsable ids; MaxArraySize") {
  const auto m = parse_sacct("11_1|TIMEOUT|0:15\n11_1.batch|CANCELLED|0:15\n12|OUT_OF_MEMORY|0:125\n");
  REQUIRE(m.size() == 2);
  CHECK(m.at("11_1") == "TIMEOUT");
  CHECK(m.at("12") == "OUT_OF_MEMORY");
  CHECK(parse_sbatch_id("1234\n") == "1234");
  CHECK(parse_sbatch_id("1234;cluster2\n") == "1234");
  CHECK(parse_sbatch_id("sbatch: error: Batch job submission failed\n").empty());
  CHECK(parse_max_array_size("MaxArraySize            = 8\nMaxJobCount             = 10000\n") == 8);
  CHECK(parse_max_array_size("nothing") == 0);
}

TEST_CASE("Slurm time values in minutes (sbatch(1) formats)") {
  CHECK(slurm_time_minutes("30") == 30);
  CHECK(slurm_time_minutes("30:30") == Approx(30.5));
  CHECK(slurm_time_minutes("1:30:00") == 90);
  CHECK(slurm_time_minutes("2-00") == 2880);
  CHECK(slurm_time_minutes("1-2:30") == 1440 + 150);
  CHECK(slurm_time_minutes("1-0:0:30") == Approx(1440.5));
  CHECK(slurm_time_minutes("") == -1);
  CHECK(slurm_time_minutes("ten") == -1);
  CHECK(slurm_time_minutes("1::2") == -1);
}

TEST_CASE("--time is smi-lua's timeout plus a margin, or the user's value when it leaves one") {
  ExecutorConfig c;
  c.kind = "slurm";
  CHECK(SlurmExecutor::time_limit_minutes(c, 0) == -1);
  CHECK(SlurmExecutor::time_limit_minutes(c, 600) == 12);   // (600 + 60 + 30) / 60 -> 12
  CHECK(SlurmExecutor::time_limit_minutes(c, 3600) == 67);  // 3600 + 360 + 30 = 3990 s -> 67
  c.set("time=30");
  CHECK(SlurmExecutor::time_limit_minutes(c, 600) == 30);
  CHECK_THROWS_WITH(SlurmExecutor::time_limit_minutes(c, 1790), Catch::Contains("no margin"));
}

TEST_CASE("the sbatch line: array with throttle, options in order, extra arguments last") {
  ExecutorConfig c;
  c.kind = "slurm";
  for (const char* kv : {"partition=short", "account=proj1", "qos=low", "mem=2G", "cpus=4", "throttle=7",
                         "sbatch=--gres=gpu:1 --constraint=avx2"})
    c.set(kv);
  const auto a = SlurmExecutor::sbatch_argv(c, "smi-m-x-0", 5, 100, "/r/.slurm/smi-m-x-0");
  const std::vector<std::string> want = {"sbatch", "--parsable", "--job-name=smi-m-x-0", "--array=0-4%7",
                                         "--output=/r/.slurm/smi-m-x-0/%a.out", "--chdir=/r/.slurm/smi-m-x-0",
                                         "--requeue", "--export=NONE", "--partition=short", "--account=proj1", "--qos=low",
                                         "--time=4", "--mem=2G", "--cpus-per-task=4", "--gres=gpu:1",
                                         "--constraint=avx2"};
  CHECK(a == want);
}

TEST_CASE("executor options: unknown keys, bad values and options smi-lua sets itself are named") {
  ExecutorConfig c;
  CHECK_THROWS_WITH(c.set("partiton=x"), Catch::Contains("unknown executor option 'partiton'") && Catch::Contains("partition"));
  CHECK_THROWS_WITH(c.set("cpus=two"), Catch::Contains("cpus=two"));
  CHECK_THROWS_WITH(c.set("time=soon"), Catch::Contains("time=soon"));
  CHECK_THROWS_WITH(c.set("nokey"), Catch::Contains("KEY=VALUE"));
  c.set("kind=pbs");
  CHECK_THROWS_WITH(c.validate(), Catch::Contains("'pbs'"));
  ExecutorConfig d;
  d.set("sbatch=--output=/etc/x");
  CHECK_THROWS_WITH(d.validate(), Catch::Contains("--output=/etc/x"));
  ExecutorConfig e;
  e.set("poll=10");
  e.set("poll_max=5");
  CHECK_THROWS_WITH(e.validate(), Catch::Contains("poll_max"));
}

TEST_CASE("scheduler commands: output captured, a hung command killed at its time limit") {
  const auto r = run_command({"sh", "-c", "echo out; echo err >&2; exit 3"}, 5);
  CHECK(r.status == 3);
  CHECK(r.out == "out\n");
  CHECK(r.err == "err\n");
  CHECK_FALSE(transient_failure(r));
  const double t0 = monotonic_seconds();
  const auto h = run_command({"sleep", "30"}, 0.3);
  CHECK(h.timed_out);
  CHECK(monotonic_seconds() - t0 < 5);
  CHECK(transient_failure(h));
  CommandResult down;
  down.status = 1;
  down.err = "squeue: error: Unable to contact slurm controller (connect failure)\n";
  CHECK(transient_failure(down));
  const auto missing = run_command({"no-such-slurm-tool-here"}, 5);
  CHECK(missing.status == -1);
  CHECK_FALSE(transient_failure(missing));  // fails at once, naming the tool, not after down_after
  CHECK_THAT(missing.err, Catch::Contains("no-such-slurm-tool-here") && Catch::Contains("slurm-client"));
}

TEST_CASE("the pending table: a job recorded before sbatch answers, its id set after, a retry's row kept") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("smi-pending-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    Store store((dir / "evaluations.sqlite").string(), false);
    PendingTable p(store.handle());
    CHECK_FALSE(p.find("k1"));
    p.put({{"k1", "smi-m-ab-0", "", 0, 1, "/runs/k1"}, {"k2", "smi-m-ab-0", "", 1, 1, "/runs/k2"}});
    CHECK(p.find("k2")->job_id.empty());  // smi-lua killed here: a rerun looks the job name up
    p.set_job_id("smi-m-ab-0", "417");
    const auto r = p.find("k2");
    REQUIRE(r);
    CHECK(r->job_id == "417");
    CHECK(r->array_index == 1);
    CHECK(r->workdir == "/runs/k2");
    // attempt 2 of k1 replaces attempt 1; finishing attempt 1 must not erase it
    p.put({{"k1", "smi-m-cd-0", "420", 0, 2, "/runs/k1"}});
    p.erase("k1", "417");
    REQUIRE(p.find("k1"));
    CHECK(p.find("k1")->attempt == 2);
    p.erase("k1", "420");
    CHECK_FALSE(p.find("k1"));
    CHECK(p.count() == 1);
  }
  {  // it lives in the store's file: a new process sees it
    Store store((dir / "evaluations.sqlite").string(), false);
    PendingTable p(store.handle());
    CHECK(p.find("k2")->job_id == "417");
  }
  fs::remove_all(dir);
}
