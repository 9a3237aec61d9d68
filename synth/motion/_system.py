"""The loop-closure equations of a linkage in link poses (placeholder for the first commit)."""

__all__ = ["check_movable"]


def check_movable(linkage) -> str | None:
    """None if the inputs can move the pose, else why not."""
    return None
