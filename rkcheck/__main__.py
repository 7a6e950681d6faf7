"""``python -m rkcheck`` = the ``rkcheck`` program."""

from rkcheck.program import main

if __name__ == "__main__":
    main()
