"""Polycubes for the census tests."""

#: A polycube of 14 cubes in the style of Demaine, Demaine, Eppstein and O'Rourke's zipless polycubes: its
#: surface is a 2-manifold of genus 0 whose 26 odd corners outnumber its 18 even corners and 6 even flat
#: vertices together by two, so no cut path (alternating colours) holds every corner: no edge-unzipping.
#: Found by a hill climb on the colour count from a 2 x 2 x 2 block.
ZIPLESS_14 = [
    [0, 2, 2], [1, 1, 1], [1, 1, 2], [1, 2, 1], [1, 2, 2], [1, 2, 3], [1, 3, 2], [2, 0, 1], [2, 1, 0], [2, 1, 1],
    [2, 1, 2], [2, 2, 1], [2, 2, 2], [3, 1, 1],
]

#: A polycube of 17 cubes with no edge-unzipping that the colour count does not show (its 31 even corners
#: need all 23 odd corners and 7 odd flat vertices, and every such path folds into an overlap): the
#: unzipping search proves it, with 138 overlap no-goods, in a few seconds.  Found by a hill climb on the
#: colour count from a 2 x 2 x 2 block, each shape near the bound given to the search.
ZIPLESS_17 = [
    [0, 2, 2], [1, 1, 2], [1, 1, 3], [1, 2, 2], [1, 2, 3], [1, 3, 2], [2, 0, 3], [2, 1, 2], [2, 1, 3], [2, 1, 4],
    [2, 2, 0], [2, 2, 1], [2, 2, 2], [2, 2, 3], [2, 3, 0], [3, 1, 3], [3, 2, 1],
]
