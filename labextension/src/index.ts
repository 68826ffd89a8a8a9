/**
 * twolink-figure-alt: image outputs in JupyterLab get their text alternative.
 *
 * twolink's inline figures (twolink_course/inline.py) store a text alternative in the
 * output's metadata, {"image/png": {"width": W, "height": H, "alt": "..."}}.
 * JupyterLab's own image renderer (RenderedImage -> renderImage in
 * @jupyterlab/rendermime) reads width and height there but never alt, so a
 * screen reader announces nothing for a figure.  This mime extension replaces
 * the renderer of image/png, image/jpeg and image/gif by a subclass of
 * JupyterLab's: the same <img> (size, background class, unconfined), plus
 * alt when the metadata carries a string alt.  Without one, nothing changes.
 */
import { RenderedImage } from '@jupyterlab/rendermime';
import { IRenderMime } from '@jupyterlab/rendermime-interfaces';

/** The image types IPython's formatters emit as base64 bitmaps (not SVG, not bmp/webp). */
const MIME_TYPES = ['image/png', 'image/jpeg', 'image/gif'];

/**
 * JupyterLab's image renderer, then `alt` from `metadata[mimeType].alt`.
 */
export class RenderedImageWithAlt extends RenderedImage {
  async render(model: IRenderMime.IMimeModel): Promise<void> {
    // JupyterLab builds the <img> exactly as it always does.
    await super.render(model);
    // The metadata of this type is any JSON value; `?.alt` of a non-object is undefined.
    const metadata = model.metadata[this.mimeType] as { alt?: unknown } | null;
    const alt = metadata?.alt;
    // Only a string is a text alternative; anything else leaves the <img> as
    // JupyterLab made it (no alt attribute is invented).
    const img = this.node.querySelector('img');
    if (img && typeof alt === 'string') {
      img.alt = alt;
    }
  }
}

/**
 * The renderer factory.  The registry keeps one factory per mime type, the
 * one added last: mime extensions are added after JupyterLab's standard
 * factories, so this one replaces the standard image renderer for these
 * types.  Its rank is the standard image factory's (90, before text/plain's
 * 120), so which of an output's representations is shown does not change.
 */
export const rendererFactory: IRenderMime.IRendererFactory = {
  safe: true,
  mimeTypes: MIME_TYPES,
  defaultRank: 90,
  createRenderer: options => new RenderedImageWithAlt(options)
};

const extension: IRenderMime.IExtension = {
  id: 'twolink-figure-alt:images',
  description: 'Image outputs get their alt text from the output metadata.',
  rendererFactory
};

export default extension;
