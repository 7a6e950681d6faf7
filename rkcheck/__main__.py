"""``python -m rkcheck`` = the ``rkcheck`` command."""

from .cli import main

if __name__ == "__main__":
    main()
