"""No literal binding numbers: every binding point of every shader is a name from its folder's bindings.h,
the header the C++ that binds it includes too (nvpro's common.h idea, issue 25). A number written in a
layout(binding = N) or in a glBind*(..., N, ...) call is a second copy of a fact that can drift from the
other side without any compiler noticing."""
import os
import re
import subprocess
import unittest

from synthetic import SCRIPTS

ROOT = os.path.dirname(SCRIPTS)
GLSL = re.compile(r"\bbinding\s*=\s*[0-9]")
# The binding point is the first argument of glBindImageTexture, glBindTextureUnit and glBindSampler, the
# second of glBindBufferBase and glBindBufferRange.
CPP = re.compile(r"\bglBind(?:ImageTexture|TextureUnit|Sampler)\(\s*[0-9]|\bglBindBuffer(?:Base|Range)\(\s*\w+\s*,\s*[0-9]")


def tracked(prefix):
    out = subprocess.run(["git", "ls-files", prefix], cwd=ROOT, capture_output=True, text=True)
    return None if out.returncode != 0 else out.stdout.splitlines()


def literal_bindings(files, pattern):
    found = []
    for f in files:
        with open(os.path.join(ROOT, f), encoding="utf-8", errors="replace") as fh:
            for line_no, line in enumerate(fh, 1):
                if pattern.search(line.split("//")[0]):
                    found.append(f"{f}:{line_no}: {line.strip()}")
    return found


class BindingTest(unittest.TestCase):
    def setUp(self):
        self.shaders, self.micro = tracked("shaders"), tracked("micro")
        if self.shaders is None:
            self.skipTest("not a git checkout")

    def test_no_literal_binding_in_shaders(self):
        self.assertEqual(literal_bindings(self.shaders, GLSL), [])

    def test_no_literal_binding_in_cpp(self):
        self.assertEqual(literal_bindings(self.micro, CPP), [])

    def test_a_literal_binding_is_found(self):
        # Both checks can fail: a probe with a literal binding in a shader and in a C++ call is reported.
        probe = os.path.join(ROOT, "shaders", "_probe_bindings.frag")
        with open(probe, "w", encoding="utf-8") as f:
            f.write("layout(std430, binding = SORT_BENCH_IN_BINDING) buffer A { uint a[]; };\n"
                    "layout(std430, binding=3) buffer B { uint b[]; };\n"
                    "  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffer);\n"
                    "  glBindTextureUnit(PRESENT_IMAGE_UNIT, image);\n"
                    "  glBindImageTexture(4, counts, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);\n")
        name = "shaders/_probe_bindings.frag"
        try:
            self.assertEqual([s.split(":")[1] for s in literal_bindings([name], GLSL)], ["2"])
            self.assertEqual([s.split(":")[1] for s in literal_bindings([name], CPP)], ["3", "5"])
        finally:
            os.remove(probe)


if __name__ == "__main__":
    unittest.main()
