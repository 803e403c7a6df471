"""Builds the optional compiled parts of the catalog: the strip filter and the arrangement
search.  Without a C compiler the install still succeeds: the catalog then uses the numpy
filter (``--method numpy``), and ``--generator loops`` says it was not built."""

import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext


class OptionalBuildExt(build_ext):
    def run(self) -> None:
        try:
            super().run()
        except Exception as exc:  # no compiler, no Python headers
            self._skip("the compiled strip filter and arrangement search were", exc)

    def build_extension(self, ext: Extension) -> None:
        try:
            super().build_extension(ext)
        except Exception as exc:
            part = "strip filter" if "_strips" in ext.name else "arrangement search"
            self._skip(f"the compiled {part} was", exc)

    @staticmethod
    def _skip(what: str, exc: Exception) -> None:
        print(f"polyloops: {what} not built ({exc}); the catalog will use the numpy filter, "
              "and only plantri's generator", file=sys.stderr)


setup(
    ext_modules=[Extension(f"polyloops.enumerate.{name}", [f"src/polyloops/enumerate/{name}.c"],
                           extra_compile_args=["-O2"], optional=True)
                 for name in ("_strips", "_arrangements")],
    cmdclass={"build_ext": OptionalBuildExt},
)
