// The page's elements that several modules draw on or listen to.

export const $ = (id) => document.getElementById(id);
export const pictureCanvas = $("picture"), cloudCanvas = $("cloud"), sideCanvas = $("map-side"), topCanvas = $("map-top");
