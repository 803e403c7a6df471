"""Builds the optional compiled strip filter; without a C compiler the install still succeeds
and the catalog falls back to the numpy filter (``--method numpy``)."""

import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext


class OptionalBuildExt(build_ext):
    def run(self) -> None:
        try:
            super().run()
        except Exception as exc:  # no compiler, no Python headers
            self._skip(exc)

    def build_extension(self, ext: Extension) -> None:
        try:
            super().build_extension(ext)
        except Exception as exc:
            self._skip(exc)

    @staticmethod
    def _skip(exc: Exception) -> None:
        print(f"polyloops: the compiled strip filter was not built ({exc}); "
              "the catalog will use the numpy filter", file=sys.stderr)


setup(
    ext_modules=[Extension(f"polyloops.enumerate.{name}", [f"src/polyloops/enumerate/{name}.c"],
                           extra_compile_args=["-O2"], optional=True)
                 for name in ("_strips", "_arrangements")],
    cmdclass={"build_ext": OptionalBuildExt},
)
