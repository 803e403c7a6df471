"""Builds the optional compiled parts: the catalog's strip filter and arrangement search, the
kernel's canonical form of small structures and count of additions, and the pictures' depth
buffer.  Without a C compiler the install still succeeds: without the arrangement search the
catalog uses plantri's generator, without the strip filter that generator uses its numpy
filter (the same records either way), and ``polyloops catalog`` says so when it runs; without
the others the same canonical forms, counts and pictures are computed in Python, slower."""

import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

CATALOG_NOTE = " (the same records, slower); 'polyloops catalog' says so when it runs"
INSTEAD = {
    "_strips": ("the compiled strip filter", "plantri's generator will use the numpy filter" + CATALOG_NOTE),
    "_arrangements": ("the compiled arrangement search",
                      "the catalog will use plantri's generator" + CATALOG_NOTE),
    "_torus": ("the compiled second stage of the torus search",
               "the genus-1 search runs in Python (the same records, much slower)"),
    "_regions": ("the compiled region search of the torus",
                 "the genus-1 second stage runs in Python (the same records, much slower)"),
    "_squares": ("the compiled first stage of the torus search",
                 "the two-axis arrangements are listed in Python (the same records, much slower)"),
    "_canonical": ("the compiled canonical form",
                   "canonical forms of small structures are computed in Python (the same forms, slower)"),
    "_cycles": ("the compiled count of additions",
                "additions are counted in Python (the same counts, slower)"),
    "_raster": ("the compiled depth buffer", "pictures are drawn in Python (the same pictures, slower)"),
}


class OptionalBuildExt(build_ext):
    def run(self) -> None:
        try:
            super().run()
        except Exception as exc:  # no compiler, no Python headers
            self._skip("no compiled part (strip filter, arrangement search, canonical form, addition count, "
                       "depth buffer) was built", exc,
                       "everything runs in Python" + CATALOG_NOTE)

    def build_extension(self, ext: Extension) -> None:
        try:
            super().build_extension(ext)
        except Exception as exc:
            what, instead = INSTEAD[ext.name.rsplit(".", 1)[1]]
            self._skip(f"{what} was not built", exc, instead)

    @staticmethod
    def _skip(what: str, exc: Exception, instead: str) -> None:
        print(f"polyloops: {what} ({exc}); {instead}", file=sys.stderr)


setup(
    ext_modules=[Extension(f"polyloops.{name.replace('/', '.')}", [f"src/polyloops/{name}.c"],
                           extra_compile_args=["-O2"], optional=True)
                 for name in ("generate/plantri/_strips", "generate/loops/_arrangements",
                              "generate/torus/_torus", "generate/torus/_regions", "generate/torus/_squares",
                              "core/_canonical",
                              "core/_cycles", "render/_raster")],
    cmdclass={"build_ext": OptionalBuildExt},
)
