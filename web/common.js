// What the playground and awl serve's online page share: a script error is set on the body
// (where the browser tests look for it), and `$` finds an element by id.
"use strict";

window.addEventListener("error", function (event) {
  document.body.setAttribute("data-error", String(event.message));
});
window.addEventListener("unhandledrejection", function (event) {
  document.body.setAttribute("data-error", String(event.reason));
});

const $ = (id) => document.getElementById(id);
