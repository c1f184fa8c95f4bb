"""``python -m mrsuspension``: the ``mrsus`` command."""

from mrsuspension.cli import main

main()
