"""The `rdem` command installed by the Python package: the same program as the Rust binary."""

import sys

from ._rdem import cli


def main() -> None:
    """Runs rdem with the command line's arguments and exits with its status."""
    sys.exit(cli(sys.argv[1:]))


if __name__ == "__main__":
    main()
