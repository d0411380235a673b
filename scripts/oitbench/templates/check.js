
window.addEventListener("load", function () {
  var imgs = Array.prototype.slice.call(document.images);
  var broken = imgs.filter(function (i) { return !i.complete || i.naturalWidth === 0; })
                   .map(function (i) { return i.getAttribute("src"); });
  var figures = imgs.filter(function (i) { return i.classList.contains("figure"); }).length;
  var paper = imgs.filter(function (i) { return i.classList.contains("paper-figure"); }).length;
  var summary = imgs.filter(function (i) { return i.classList.contains("summary-figure"); }).length;
  document.body.setAttribute("data-paper-figures", String(paper));
  document.body.setAttribute("data-summary-figures", String(summary));
  document.body.setAttribute("data-images", String(imgs.length));
  document.body.setAttribute("data-figures", String(figures));
  document.body.setAttribute("data-broken", JSON.stringify(broken));
  document.body.setAttribute("data-loaded", "1");
  if (broken.length) {
    var box = document.getElementById("broken-images");
    box.textContent = broken.length + " image(s) did not load: " + broken.join(", ");
    box.hidden = false;
  }
});
