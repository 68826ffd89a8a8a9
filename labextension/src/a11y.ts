/**
 * twolink-figure-alt:a11y: two accessibility gaps of what JupyterLab renders
 * in output areas, closed in the DOM without changing how anything looks.
 *
 * 1. Slider handles without a name.  ipywidgets 8.1 builds its sliders
 *    (IntSlider, FloatSlider, FloatLogSlider, the range and selection
 *    sliders: every view with the class `widget-slider`) on noUiSlider, whose
 *    handles are `<div class="noUi-handle" role="slider">`; ipywidgets never
 *    passes noUiSlider's `handleAttributes`, so a handle has no accessible
 *    name, and the widget's description is a separate
 *    `<label class="widget-label">` associated with nothing (axe:
 *    aria-input-field-name).  Each handle without a name of its own gets
 *    `aria-labelledby` pointing to that label (which gets an id if it has
 *    none), so the name follows the description as it changes.  ipywidgets
 *    hides the label (display: none) exactly when the description is empty,
 *    and then keeps the previous text in it: a hidden or empty label names
 *    nothing, and the handle is left without a name rather than given an
 *    invented or stale one (the readout is its value, already its
 *    aria-valuetext).
 *
 * 2. Scrollable outputs the keyboard cannot reach.  JupyterLab's output
 *    elements (`.jp-OutputArea-output`) are scroll containers (overflow:
 *    auto); content wider than the notebook, e.g. a matrix typeset by MathJax
 *    in a `text/latex` output, scrolls inside them, but the element is not
 *    focusable and holds nothing focusable, so without a mouse the clipped
 *    part cannot be scrolled into view (axe: scrollable-region-focusable,
 *    WCAG 2.1.1).  Such an output, while it overflows, gets `tabindex="0"`
 *    (removed again when it no longer does); while it has focus, the Left and
 *    Right arrow keys scroll it, as in any page, instead of reaching
 *    JupyterLab's command-mode shortcuts (collapse and expand headings).
 *
 * 3. Videos that play by themselves.  The course's animations are H.264
 *    videos with `autoplay loop` (matplotlib's tag).  For a reader who asks
 *    the system for reduced motion (`prefers-reduced-motion: reduce`), a
 *    video in an output area loses `autoplay` as it is added and stays on its
 *    first frame until played with its controls (WCAG 2.2.2); when the
 *    preference is dropped again, `autoplay` comes back to the videos it was
 *    taken from (they start when played or re-rendered).
 *
 * Cheap: one MutationObserver on the document, reacting only to added nodes
 * in or containing an output area (`.jp-OutputArea`); the sizes of outputs
 * are read in a ResizeObserver's callback, after layout, never forcing one.
 */
import type { IPlugin } from '@lumino/coreutils';

/** Marks what this plugin set, so it only ever updates or removes its own attributes. */
const MARK_NAME = 'data-twolink-a11y-name';
const MARK_SCROLL = 'data-twolink-a11y-scroll';

const OUTPUT_AREA = '.jp-OutputArea';
const OUTPUT = '.jp-OutputArea-output';
const SLIDER_WIDGET = '.widget-slider';
const HANDLE = '.noUi-handle[role="slider"]';
/** An ipywidgets widget output: interactive, it lays itself out (its handles are named above). */
const WIDGET_VIEW = 'application/vnd.jupyter.widget-view+json';
/** Elements in the tab order (what axe's focusable-content check looks for). */
const FOCUSABLE = [
  'a[href]',
  'area[href]',
  'button',
  'input:not([type="hidden"])',
  'select',
  'textarea',
  'iframe',
  'summary',
  'audio[controls]',
  'video[controls]',
  '[contenteditable=""]',
  '[contenteditable="true"]',
  '[tabindex]'
]
  .map(selector => `${selector}:not([tabindex^="-"])`)
  .join(', ');

let labelCount = 0;

// --- 1. slider handles -------------------------------------------------------

/** The widget's description label: the first `.widget-label` child of the slider widget. */
function descriptionLabel(widget: Element): HTMLElement | null {
  for (const child of Array.from(widget.children)) {
    if (child instanceof HTMLElement && child.classList.contains('widget-label')) {
      return child;
    }
  }
  return null;
}

/** A label that names something: shown (ipywidgets hides it when there is no description) and not blank. */
function labelNames(label: HTMLElement | null): label is HTMLElement {
  return (
    label !== null &&
    !label.hidden &&
    label.style.display !== 'none' &&
    (label.textContent ?? '').trim() !== ''
  );
}

/** A name the handle has from elsewhere (noUiSlider's handleAttributes, an author). */
function hasOwnName(handle: Element): boolean {
  if (handle.hasAttribute(MARK_NAME)) {
    return false;
  }
  return ['aria-label', 'aria-labelledby', 'title'].some(
    attribute => (handle.getAttribute(attribute) ?? '').trim() !== ''
  );
}

/** Watches the labels in use: ipywidgets hides or shows one through its style alone. */
const labelStyles = new MutationObserver(records => {
  for (const record of records) {
    const widget = (record.target as Element).parentElement;
    if (widget) {
      nameHandles(widget);
    }
  }
});
const watchedLabels = new WeakSet<Element>();

/** Names the handles of one slider widget after its label, or removes the name this plugin gave. */
function nameHandles(widget: Element): void {
  const label = descriptionLabel(widget);
  if (label && !watchedLabels.has(label)) {
    watchedLabels.add(label);
    labelStyles.observe(label, { attributes: true, attributeFilter: ['style', 'hidden'] });
  }
  for (const handle of Array.from(widget.querySelectorAll(HANDLE))) {
    if (hasOwnName(handle)) {
      continue;
    }
    if (labelNames(label)) {
      if (!label.id) {
        label.id = `twolink-widget-label-${++labelCount}`;
      }
      if (handle.getAttribute('aria-labelledby') !== label.id) {
        handle.setAttribute('aria-labelledby', label.id);
      }
      handle.setAttribute(MARK_NAME, '');
    } else if (handle.hasAttribute(MARK_NAME)) {
      handle.removeAttribute('aria-labelledby');
      handle.removeAttribute(MARK_NAME);
    }
  }
}

// --- 2. scrollable outputs ---------------------------------------------------

const keyedOutputs = new WeakSet<Element>();
const observedOutputs = new Set<Element>();

function scrollsX(output: Element, style: CSSStyleDeclaration): boolean {
  return /auto|scroll/.test(style.overflowX) && output.scrollWidth > output.clientWidth;
}

/** Left/Right scroll the focused output; JupyterLab (its keydown listener is on the document) does not see them. */
function onKeydown(this: HTMLElement, event: KeyboardEvent): void {
  if (
    event.target === this &&
    (event.key === 'ArrowLeft' || event.key === 'ArrowRight') &&
    !(event.altKey || event.ctrlKey || event.metaKey || event.shiftKey) &&
    scrollsX(this, getComputedStyle(this))
  ) {
    event.stopPropagation();
  }
}

/** After layout: outputs that overflow without anything focusable in them become focusable. */
const outputSizes = new ResizeObserver(entries => {
  for (const entry of entries) {
    const output = entry.target as HTMLElement;
    if (!output.isConnected) {
      outputSizes.unobserve(output);
      observedOutputs.delete(output);
      continue;
    }
    if (entry.contentRect.width === 0 && entry.contentRect.height === 0) {
      continue; // not rendered (a hidden tab): nothing to measure, leave it as it is
    }
    const style = getComputedStyle(output);
    const scrolls =
      scrollsX(output, style) ||
      (/auto|scroll/.test(style.overflowY) && output.scrollHeight > output.clientHeight);
    const ours = output.hasAttribute(MARK_SCROLL);
    if (scrolls && !ours && !output.hasAttribute('tabindex') && !output.querySelector(FOCUSABLE)) {
      output.tabIndex = 0;
      output.setAttribute(MARK_SCROLL, '');
      if (!keyedOutputs.has(output)) {
        keyedOutputs.add(output);
        output.addEventListener('keydown', onKeydown);
      }
    } else if (ours && (!scrolls || output.querySelector(FOCUSABLE))) {
      output.removeAttribute('tabindex');
      output.removeAttribute(MARK_SCROLL);
    }
  }
});

/** (Re)measure an output after the next layout: observing anew reports its current size. */
function measure(output: Element): void {
  if (output.getAttribute('data-mime-type') === WIDGET_VIEW) {
    return;
  }
  outputSizes.unobserve(output);
  outputSizes.observe(output);
  observedOutputs.add(output);
}

function forgetDetached(): void {
  for (const output of observedOutputs) {
    if (!output.isConnected) {
      outputSizes.unobserve(output);
      observedOutputs.delete(output);
    }
  }
}

// --- 3. videos and reduced motion ---------------------------------------------

const REDUCED_MOTION = '(prefers-reduced-motion: reduce)';
/** Marks a video whose autoplay this plugin took away (and gives back). */
const MARK_MOTION = 'data-twolink-a11y-autoplay';
const reducedMotion = window.matchMedia?.(REDUCED_MOTION);

/** A video that would play by itself stays still for a reader who asks for reduced motion. */
function holdStill(video: HTMLVideoElement): void {
  if (!reducedMotion?.matches || !video.hasAttribute('autoplay')) {
    return;
  }
  video.removeAttribute('autoplay');
  video.autoplay = false;
  video.setAttribute(MARK_MOTION, '');
  video.pause();
}

/** The reader's preference changed: hold every video still, or give autoplay back. */
function onMotionPreference(): void {
  const videos = document.querySelectorAll<HTMLVideoElement>(`${OUTPUT_AREA} video`);
  for (const video of Array.from(videos)) {
    if (reducedMotion?.matches) {
      holdStill(video);
    } else if (video.hasAttribute(MARK_MOTION)) {
      video.removeAttribute(MARK_MOTION);
      video.setAttribute('autoplay', '');
    }
  }
}

// --- what to look at ------------------------------------------------------------

/** The slider widgets and outputs at or under `node` (or around it, for the closest ones). */
function visit(node: Element, widgets: Set<Element>, outputs: Set<Element>): void {
  const widget = node.closest(SLIDER_WIDGET);
  if (widget) {
    widgets.add(widget);
  }
  const output = node.closest(OUTPUT);
  if (output) {
    outputs.add(output);
  }
  node.querySelectorAll(SLIDER_WIDGET).forEach(found => widgets.add(found));
  node.querySelectorAll(OUTPUT).forEach(found => outputs.add(found));
  if (node instanceof HTMLVideoElement) {
    holdStill(node);
  }
  node.querySelectorAll('video').forEach(holdStill);
}

function onMutations(records: MutationRecord[]): void {
  const widgets = new Set<Element>();
  const outputs = new Set<Element>();
  for (const record of records) {
    if (!record.addedNodes.length || !(record.target instanceof Element)) {
      continue;
    }
    const target = record.target;
    if (target.closest(OUTPUT_AREA)) {
      // something was added in an output area: new outputs, widgets, handles,
      // a label's new text, MathJax's typeset math
      for (const node of Array.from(record.addedNodes)) {
        if (node instanceof Element) {
          visit(node, widgets, outputs);
        }
      }
      const label = target.closest('.widget-label');
      if (label?.parentElement) {
        widgets.add(label.parentElement);
      }
      const output = target.closest(OUTPUT);
      if (output) {
        outputs.add(output);
      }
    } else {
      // a notebook, a cell or an output area attached with its outputs
      for (const node of Array.from(record.addedNodes)) {
        if (node instanceof Element && node.querySelector(OUTPUT_AREA)) {
          visit(node, widgets, outputs);
        }
      }
    }
  }
  update(widgets, outputs);
}

function update(widgets: Set<Element>, outputs: Set<Element>): void {
  widgets.forEach(nameHandles);
  if (outputs.size) {
    forgetDetached();
    outputs.forEach(measure);
  }
}

/** Everything already there, then every addition. */
function start(): void {
  const widgets = new Set<Element>();
  const outputs = new Set<Element>();
  visit(document.body, widgets, outputs);
  update(widgets, outputs);
  new MutationObserver(onMutations).observe(document.body, {
    childList: true,
    subtree: true
  });
  reducedMotion?.addEventListener?.('change', onMotionPreference);
  // MathJax's web fonts change the width of typeset math without a mutation
  document.fonts?.addEventListener?.('loadingdone', () => {
    observedOutputs.forEach(measure);
  });
}

const plugin: IPlugin<unknown, void> = {
  id: 'twolink-figure-alt:a11y',
  description:
    "ipywidgets' slider handles are named by the widget's description; outputs that scroll are reachable with the keyboard; videos do not play by themselves for readers who ask for reduced motion.",
  autoStart: true,
  activate: () => {
    start();
  }
};

export default plugin;
