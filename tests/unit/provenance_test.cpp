// Run identity and machine identity (issue 31): run ids, --tag parsing and its column encoding, the
// machine fingerprint from /proc text, llvmpipe's LLVM and vector width from GL strings.
#include "core/provenance.hpp"

#include <gtest/gtest.h>

#include <set>

#include "core/params.hpp"

namespace oitbench {

TEST(RunId, IsARandomVersion4Uuid) {
  std::set<std::string> seen;
  for (int i = 0; i < 100; ++i) {
    auto id = new_run_id();
    ASSERT_TRUE(is_run_id(id)) << id;
    EXPECT_EQ(id[14], '4') << id;
    EXPECT_NE(std::string("89ab").find(id[19]), std::string::npos) << id;
    seen.insert(id);
  }
  EXPECT_EQ(seen.size(), 100u);
  EXPECT_FALSE(is_run_id("0F8FAD5B-D9CB-469F-A165-70867728950E"));
  EXPECT_FALSE(is_run_id("0f8fad5b-d9cb-469f-a165-70867728950"));
  EXPECT_FALSE(is_run_id("not-a-uuid"));
}

TEST(Tags, ParseSortAndEncodeWithEscapes) {
  Tags t = parse_tags({"pool=ci;nightly", "mesa=22.3.6", "job=https://ci/x?a=1&b=2%"});
  EXPECT_EQ(t.size(), 3u);
  EXPECT_EQ(t["job"], "https://ci/x?a=1&b=2%");
  std::string col = encode_tags(t);
  EXPECT_EQ(col, "job=https://ci/x?a%3D1&b%3D2%25;mesa=22.3.6;pool=ci%3Bnightly");
  EXPECT_EQ(decode_tags(col), t);
  EXPECT_EQ(encode_tags({}), "");
  EXPECT_TRUE(decode_tags("").empty());
  EXPECT_EQ(parse_tags({"k="})["k"], "");
}

TEST(Tags, BadTagsAreUsageErrorsNamingTheOption) {
  auto message = [](std::vector<std::string> specs) {
    try {
      parse_tags(specs);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({"novalue"}).find("--tag novalue: give KEY=VALUE"), std::string::npos);
  EXPECT_NE(message({"=x"}).find("--tag =x: the key"), std::string::npos);
  EXPECT_NE(message({"1abc=x"}).find("must start with a letter"), std::string::npos);
  EXPECT_NE(message({"a b=x"}).find("--tag"), std::string::npos);
  EXPECT_NE(message({std::string(65, 'k') + "=x"}).find("at most 64"), std::string::npos);
  EXPECT_NE(message({"a=1", "b=2", "a=3"}).find("--tag a: the key is given twice"), std::string::npos);
  EXPECT_NE(message({"a=line\nbreak"}).find("control character"), std::string::npos);
  EXPECT_EQ(message({"a.b-c_d=1"}), "no error");
}

namespace {

const char* kCpuinfo =
    "processor\t: 0\nvendor_id\t: AuthenticAMD\ncpu family\t: 25\nmodel\t\t: 1\nmodel name\t: AMD EPYC\n"
    "stepping\t: 1\nflags\t\t: fpu sse2 ssse3 sse4_1 sse4_2 avx avx2 fma avx512f avx512bw avx512vl popcnt\n\n"
    "processor\t: 1\nvendor_id\t: AuthenticAMD\ncpu family\t: 25\nmodel\t\t: 1\nmodel name\t: AMD EPYC\n"
    "stepping\t: 1\nflags\t\t: fpu sse2 ssse3 sse4_1 sse4_2 avx avx2 fma avx512f avx512bw avx512vl popcnt\n\n";
const char* kMeminfo = "MemTotal:        8133508 kB\nMemFree:         1000 kB\n";

}  // namespace

TEST(MachineIdentity, ReadsTheCpuAndTellsTwoEpycsApart) {
  auto m = machine_identity(kCpuinfo, kMeminfo, "6.1.0-13-amd64 #1 SMP");
  EXPECT_EQ(m.cpu_vendor, "AuthenticAMD");
  EXPECT_EQ(m.cpu_family, "25");
  EXPECT_EQ(m.cpu_model_id, "1");
  EXPECT_EQ(m.cpu_stepping, "1");
  EXPECT_EQ(m.cpu_isa, "sse2 ssse3 sse4_1 sse4_2 popcnt avx fma avx2 avx512f avx512bw avx512vl");
  EXPECT_EQ(m.cpu_count, 2);
  EXPECT_EQ(m.memory_bytes, 8133508LL * 1024);
  ASSERT_EQ(m.fingerprint.size(), 16u);
  EXPECT_EQ(machine_identity(kCpuinfo, kMeminfo, "6.1.0-13-amd64 #1 SMP").fingerprint, m.fingerprint);
  // The same "AMD EPYC" without AVX-512: another machine.
  std::string no512 = kCpuinfo;
  for (auto pos = no512.find(" avx512f avx512bw avx512vl"); pos != std::string::npos;
       pos = no512.find(" avx512f avx512bw avx512vl"))
    no512.erase(pos, 26);
  auto other = machine_identity(no512, kMeminfo, "6.1.0-13-amd64 #1 SMP");
  EXPECT_EQ(other.cpu_isa, "sse2 ssse3 sse4_1 sse4_2 popcnt avx fma avx2");
  EXPECT_NE(other.fingerprint, m.fingerprint);
  EXPECT_NE(machine_identity(kCpuinfo, kMeminfo, "6.1.0-14-amd64 #1 SMP").fingerprint, m.fingerprint);
  EXPECT_NE(machine_identity(kCpuinfo, "MemTotal: 16000000 kB\n", "6.1.0-13-amd64 #1 SMP").fingerprint, m.fingerprint);
}

TEST(MachineIdentity, ThisMachineHasACpuAndMemory) {
  auto m = this_machine();
  EXPECT_GT(m.cpu_count, 0);
  EXPECT_GT(m.memory_bytes, 0);
  EXPECT_FALSE(m.kernel.empty());
  EXPECT_EQ(m.fingerprint.size(), 16u);
}

TEST(LlvmTarget, FromLlvmpipeAndZinkRenderers) {
  auto t = llvm_target("llvmpipe (LLVM 15.0.6, 256 bits)");
  EXPECT_EQ(t.llvm_version, "15.0.6");
  EXPECT_EQ(t.vector_bits, "256");
  EXPECT_EQ(llvm_target("zink (llvmpipe (LLVM 15.0.6, 128 bits))").vector_bits, "128");
  EXPECT_EQ(llvm_target("NVIDIA H200/PCIe/SSE2").llvm_version, "");
  EXPECT_EQ(llvm_target("AMD Radeon RX 6800 (radeonsi, navi21, LLVM 15.0.6, DRM 3.49)").llvm_version, "15.0.6");
  EXPECT_EQ(mesa_version("4.5 (Core Profile) Mesa 22.3.6"), "Mesa 22.3.6");
  EXPECT_EQ(mesa_version("4.6.0 NVIDIA 550.54.15"), "");
}

}  // namespace oitbench
