"""The joint kinds a chain can have, in one table: their names, in the order the certificate's colour
cells and stored ids depend on, and their signs in a joint list.

>>> JOINT_KINDS, SYMBOLS["prismatic"]
(('revolute', 'prismatic', 'mesh'), '=')
"""

from __future__ import annotations

__all__ = ["JOINT_KINDS", "SYMBOLS"]

#: the kinds in certificate order: a chain's nauty graph gives its joints one colour cell per kind in
#: this order (meshes only where a chain has some), so reordering them changes every stored id
JOINT_KINDS = ("revolute", "prismatic", "mesh")
#: their signs in a joint list: 0-1, 0=1, 0~1
SYMBOLS = {"revolute": "-", "prismatic": "=", "mesh": "~"}
