"""``python -m mrsuspension.cli``: the ``mrsus`` command."""

from mrsuspension.cli import main

main()
