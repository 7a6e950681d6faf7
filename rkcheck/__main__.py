"""``python -m rkcheck`` = the ``rkcheck`` command."""

from rkcheck.cli import main

if __name__ == "__main__":
    main()
