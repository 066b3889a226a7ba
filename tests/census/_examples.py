"""Polycubes for the census tests."""

#: A polycube of 43 cubes in the style of Demaine, Demaine, Eppstein and O'Rourke's zipless polycubes: its
#: surface is a 2-manifold of genus 0 whose 67 odd corners outnumber its 57 even corners and 8 even flat
#: vertices together by two, so no cut path (alternating colours) holds every corner: no edge-unzipping.
#: Found by a hill climb on the colour count from a 3 x 3 x 3 block.
ZIPLESS_43 = [
    [0, 0, 5], [1, 0, 5], [1, 0, 6], [1, 1, 3], [1, 1, 5], [1, 3, 3], [2, 0, 3], [2, 1, 2], [2, 1, 3], [2, 1, 4],
    [2, 1, 5], [2, 2, 2], [2, 2, 3], [2, 3, 3], [2, 3, 4], [2, 4, 3], [3, 1, 2], [3, 1, 3], [3, 1, 4], [3, 2, 2],
    [3, 2, 3], [3, 2, 4], [3, 3, 2], [3, 3, 3], [3, 3, 4], [3, 3, 5], [4, 0, 4], [4, 1, 3], [4, 1, 4], [4, 1, 5],
    [4, 2, 2], [4, 2, 3], [4, 2, 4], [4, 3, 1], [4, 3, 2], [4, 3, 3], [4, 3, 4], [4, 4, 0], [4, 4, 1], [4, 4, 3],
    [5, 1, 4], [5, 3, 4], [5, 4, 1],
]

#: A polycube of 17 cubes with no edge-unzipping that the colour count does not show (its 31 even corners
#: need all 23 odd corners and 7 odd flat vertices, and every such path folds into an overlap): the
#: unzipping search proves it, with 138 overlap no-goods, in a few seconds.  Found by a hill climb on the
#: colour count from a 2 x 2 x 2 block, each shape near the bound given to the search.
ZIPLESS_17 = [
    [0, 2, 2], [1, 1, 2], [1, 1, 3], [1, 2, 2], [1, 2, 3], [1, 3, 2], [2, 0, 3], [2, 1, 2], [2, 1, 3], [2, 1, 4],
    [2, 2, 0], [2, 2, 1], [2, 2, 2], [2, 2, 3], [2, 3, 0], [3, 1, 3], [3, 2, 1],
]
